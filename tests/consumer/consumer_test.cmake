# CTest registration of the installed-package test: install the project from
# this build tree into a temporary prefix, move the prefix, check that no
# package file names a path, build the two programs of tests/consumer
# against it (COMPONENTS cost_functions, and every room) and run them
# (run_consumer_test.sh). Include from tests/CMakeLists.txt with
#   include(${CMAKE_CURRENT_SOURCE_DIR}/consumer/consumer_test.cmake)
# It needs the library and the CLI built, which a complete build provides.
add_test(NAME consumer_package
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_consumer_test.sh ${PROJECT_BINARY_DIR})
set_tests_properties(consumer_package PROPERTIES TIMEOUT 600)
