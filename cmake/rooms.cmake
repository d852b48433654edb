# The rooms of the library (docs/development.md, "Layout"): one static library per folder,
# linked only to the rooms below it. Each room's CMakeLists.txt calls
#
#   shellspace_room(NAME <room> [RECURSE] [PUBLIC deps...] [PRIVATE deps...])
#
# which builds every .cc of that folder (and, with RECURSE, of its
# subfolders) into the target shellspace_<room>, exported as
# shellspace::<room>. Sources include every project header as
# "shellspace/<room>/<file>.h", their path in the checkout (the rooms live
# under shellspace/, whose parent is the build tree's include folder); an
# installed tree has the same paths under <prefix>/include/.

function(shellspace_room)
  cmake_parse_arguments(ROOM "RECURSE" "NAME" "PUBLIC;PRIVATE" ${ARGN})
  if(ROOM_RECURSE)
    file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  else()
    file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  endif()
  set(target shellspace_${ROOM_NAME})
  add_library(${target} STATIC ${sources})
  add_library(shellspace::${ROOM_NAME} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${ROOM_NAME}
    POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${SHELLSPACE_BUILD_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ROOM_PUBLIC} PRIVATE ${ROOM_PRIVATE})
  target_compile_options(${target} PRIVATE ${SHELLSPACE_WARNINGS})
  target_compile_definitions(${target} PRIVATE _USE_MATH_DEFINES)
  set_property(GLOBAL APPEND PROPERTY SHELLSPACE_ROOMS ${target})
endfunction()

# Writes FILE, the table of the layering test (tests/layering_test.sh): one
# line per room, bottom up (the order of SHELLSPACE_ROOMS),
#
#   <room> <source folder> <include prefix> : <rooms it links>
#
# from each room's LINK_LIBRARIES (its public and private
# target_link_libraries), so that the test checks the includes against the
# links the build has, not against a list of its own.
function(shellspace_write_room_table file)
  get_property(targets GLOBAL PROPERTY SHELLSPACE_ROOMS)
  set(text "# Written by cmake/rooms.cmake (shellspace_write_room_table) from the rooms' links.\n")
  foreach(target ${targets})
    get_target_property(room ${target} EXPORT_NAME)
    get_target_property(dir ${target} SOURCE_DIR)
    file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${dir})
    get_target_property(links ${target} LINK_LIBRARIES)
    set(linked "")
    foreach(item IN LISTS links)
      if(TARGET ${item})
        get_target_property(real ${item} ALIASED_TARGET)
        if(NOT real)
          set(real ${item})
        endif()
        if(real IN_LIST targets)
          get_target_property(name ${real} EXPORT_NAME)
          list(APPEND linked ${name})
        endif()
      endif()
    endforeach()
    list(JOIN linked " " linked)
    string(APPEND text "${room} ${folder} ${SHELLSPACE_INCLUDE_PREFIX}${folder} : ${linked}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
