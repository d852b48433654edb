# Installation rules: the static library (exported as shellspace::shellspace),
# the `shellspace` command-line tool, the public headers under
# include/shellspace/ and a relocatable CMake package in lib/cmake/shellspace,
# so that an outside project can do
#
#   find_package(shellspace REQUIRED)
#   target_link_libraries(app PRIVATE shellspace::shellspace)
#
# and write #include <shellspace/cost_functions/deformation_energy_residuals.h>.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SHELLSPACE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/shellspace"
  CACHE STRING "Install directory of the shellspace CMake package files")
mark_as_advanced(SHELLSPACE_INSTALL_CMAKEDIR)

# The library is static and position independent, so that consumers may link
# it into shared objects as well as executables.
install(TARGETS shellspace ${SHELLSPACE_ROOMS}
  EXPORT shellspaceTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(TARGETS shellspace_cli
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Public headers keep their source-tree layout under include/shellspace/; the
# library's own includes are "shellspace/<room>/...", so only include/ is on a
# consumer's include path.
foreach(shellspace_header_dir geometry cost_functions solvers problems io render reports)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${shellspace_header_dir}/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shellspace/${shellspace_header_dir}
    FILES_MATCHING PATTERN "*.h")
endforeach()

install(EXPORT shellspaceTargets
  NAMESPACE shellspace::
  FILE shellspaceTargets.cmake
  DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})

configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/shellspaceConfig.cmake.in
  ${PROJECT_BINARY_DIR}/shellspaceConfig.cmake
  INSTALL_DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/shellspaceConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/shellspaceConfig.cmake
  ${PROJECT_BINARY_DIR}/shellspaceConfigVersion.cmake
  ${CMAKE_CURRENT_LIST_DIR}/shellspaceSystemLibraries.cmake
  DESTINATION ${SHELLSPACE_INSTALL_CMAKEDIR})
