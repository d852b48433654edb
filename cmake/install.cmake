# Installation rules: the static libraries of the rooms, the `shellspace`
# command-line tool, the public headers under include/shellspace/ and a
# relocatable CMake package in lib/cmake/shellspace, so that an outside
# project can do
#
#   find_package(shellspace REQUIRED)
#   target_link_libraries(app PRIVATE shellspace::shellspace)
#
# and write #include <shellspace/cost_functions/deformation_energy_residuals.h>
# (only <prefix>/include is on its include path). The package's components
# are the rooms (cmake/rooms.cmake): with
#
#   find_package(shellspace REQUIRED COMPONENTS cost_functions)
#   target_link_libraries(app PRIVATE shellspace::cost_functions)
#
# the package defines only shellspace::cost_functions and the rooms below it
# (shellspace::geometry) and finds only what they link (Ceres, Eigen,
# Threads, OpenBLAS if installed); OpenMesh, libpng, tinygltf, CHOLMOD and
# UMFPACK are found only for a room that links them (calculus, io, solvers),
# and shellspace::shellspace only without COMPONENTS (every room). An unknown
# component is an error naming it.
#
# Nothing in the package names a path of the machine that built it: every
# room has its own export file (shellspace_<room>Targets.cmake), which
# names its dependencies by their imported targets; the Config finds the
# packages of those targets (find_dependency) and the libraries without a
# package (cmake/shellspaceSystemLibraries.cmake, installed with it) at the
# consumer's configure time, so the prefix can be moved after installation
# (tests/consumer/run_consumer_test.sh).
include(GNUInstallDirs)

set(SHELLSPACE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/shellspace"
  CACHE STRING "Install directory of the shellspace CMake package files")
mark_as_advanced(SHELLSPACE_INSTALL_CMAKEDIR)

# The imported targets a room may link and the package that defines each
# (<target>=<package>); the Config's find_dependency arguments of a package
# are in cmake/shellspaceConfig.cmake.in.
set(SHELLSPACE_PACKAGE_OF_TARGET
  Eigen3::Eigen=Eigen3 Threads::Threads=Threads Ceres::ceres=Ceres
  OpenMeshCore=OpenMesh OpenMeshTools=OpenMesh PNG::PNG=PNG
  TinyGLTF::TinyGLTF=TinyGLTF)

# The room table of the Config, from the rooms' link interfaces: for each
# room (bottom up, the order of SHELLSPACE_ROOMS) the rooms, packages and
# system libraries (shellspace_system::) it links directly. Anything else
# with a "::", a "/" or a generator expression is an error here, so that a
# new dependency cannot reach the package as a path or unfound.
set(SHELLSPACE_CONFIG_ROOMS "")
set(shellspace_room_names "")
foreach(target ${SHELLSPACE_ROOMS})
  get_target_property(room ${target} EXPORT_NAME)
  list(APPEND shellspace_room_names ${room})
  set(rooms "")
  set(packages "")
  set(system "")
  get_target_property(links ${target} INTERFACE_LINK_LIBRARIES)
  foreach(item IN LISTS links)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
    set(package "")
    foreach(pair IN LISTS SHELLSPACE_PACKAGE_OF_TARGET)
      if(pair MATCHES "^(.*)=(.*)$" AND item STREQUAL CMAKE_MATCH_1)
        set(package ${CMAKE_MATCH_2})
      endif()
    endforeach()
    if(package)
      list(APPEND packages ${package})
    elseif(item MATCHES "^shellspace::(.+)$")
      list(APPEND rooms ${CMAKE_MATCH_1})
    elseif(item MATCHES "^shellspace_system::(.+)$")
      list(APPEND system ${CMAKE_MATCH_1})
    elseif(item MATCHES "::|/|\\$<")
      message(FATAL_ERROR "cmake/install.cmake: ${target} links '${item}', "
        "which the installed package cannot find for its consumers: link a "
        "target of SHELLSPACE_PACKAGE_OF_TARGET or shellspace_system::")
    endif()
    # Anything else is a plain library name (${CMAKE_DL_LIBS}) for the linker.
  endforeach()
  list(REMOVE_DUPLICATES packages)
  foreach(kind rooms packages system)
    list(JOIN ${kind} " " names)
    string(APPEND SHELLSPACE_CONFIG_ROOMS "set(_shellspace_${room}_${kind} ${names})\n")
  endforeach()
endforeach()
list(JOIN shellspace_room_names " " names)
string(PREPEND SHELLSPACE_CONFIG_ROOMS "set(_shellspace_rooms ${names})\n")

# The libraries are static and position independent, so that consumers may
# link them into shared objects as well as executables. One export set per
# room, so that the Config loads only the requested rooms; the umbrella
# shellspace::shellspace in shellspaceTargets.cmake.
foreach(target ${SHELLSPACE_ROOMS})
  install(TARGETS ${target}
    EXPORT ${target}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT ${target}Targets
    NAMESPACE shellspace::
    FILE ${target}Targets.cmake
    DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})
endforeach()
install(TARGETS shellspace EXPORT shellspaceTargets)
install(EXPORT shellspaceTargets
  NAMESPACE shellspace::
  FILE shellspaceTargets.cmake
  DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})

install(TARGETS shellspace_cli
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Public headers keep their source-tree layout (shellspace/) under include/; the
# library's own includes are "shellspace/<room>/...", so only include/ is on a
# consumer's include path.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shellspace/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shellspace
  FILES_MATCHING PATTERN "*.h")

# The Config is written by configure_file, not
# configure_package_config_file: the latter's @PACKAGE_INIT@ names the
# configured install prefix, an absolute path.
include(CMakePackageConfigHelpers)
configure_file(${CMAKE_CURRENT_LIST_DIR}/shellspaceConfig.cmake.in
  ${PROJECT_BINARY_DIR}/shellspaceConfig.cmake @ONLY)
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/shellspaceConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/shellspaceConfig.cmake
  ${PROJECT_BINARY_DIR}/shellspaceConfigVersion.cmake
  ${CMAKE_CURRENT_LIST_DIR}/shellspaceSystemLibraries.cmake
  DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})
