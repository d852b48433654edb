# The libraries shellspace links that come without a CMake package of their
# own, as IMPORTED targets found (find_library, find_path) at the configure
# time of whoever includes this file: the shellspace project (top-level
# CMakeLists.txt) and a consumer of the installed package
# (shellspaceConfig.cmake, next to which this file is installed). The rooms
# link these targets by name, so that the exported files hold names, not
# paths of the machine that built the package.
#
#   shellspace_system::fast_blas  OpenBLAS, as a link option that puts it
#                                 ahead of every library: Debian's Ceres
#                                 links ATLAS' reference-speed BLAS, and
#                                 CHOLMOD's dgemm must resolve to the
#                                 optimised one (a sparse Cholesky is ~10x
#                                 faster; tests/blas_order_test.sh). An empty
#                                 target if OpenBLAS is not installed.
#   shellspace_system::cholmod    libcholmod (cholmod.h)
#   shellspace_system::umfpack    libumfpack (umfpack.h)
#
# In:  shellspace_system_libraries, the ones to define (default: all three).
# Out: shellspace_system_missing, those of them not found (never fast_blas).
# Targets already defined are kept. The cache variables SHELLSPACE_FAST_BLAS,
# SHELLSPACE_CHOLMOD_LIBRARY, SHELLSPACE_UMFPACK_LIBRARY and
# SHELLSPACE_{CHOLMOD,UMFPACK}_INCLUDE_DIR name other files.
if(NOT DEFINED shellspace_system_libraries)
  set(shellspace_system_libraries fast_blas cholmod umfpack)
endif()
set(shellspace_system_missing "")
foreach(_shellspace_library IN LISTS shellspace_system_libraries)
  if(TARGET shellspace_system::${_shellspace_library})
    continue()
  endif()
  if(_shellspace_library STREQUAL "fast_blas")
    # Debian installs libopenblas.so in the architecture's library folder
    # (the alternatives link to the chosen variant), else in its
    # openblas-pthread/ subfolder.
    find_library(SHELLSPACE_FAST_BLAS NAMES openblas
      DOC "Optimised BLAS linked ahead of Ceres' BLAS (empty: none)")
    find_library(SHELLSPACE_FAST_BLAS NAMES openblas
      PATH_SUFFIXES openblas-pthread)
    add_library(shellspace_system::fast_blas INTERFACE IMPORTED)
    if(SHELLSPACE_FAST_BLAS)
      set_property(TARGET shellspace_system::fast_blas PROPERTY
        INTERFACE_LINK_OPTIONS
        "SHELL:-Wl,--no-as-needed \"${SHELLSPACE_FAST_BLAS}\" -Wl,--as-needed")
    endif()
  elseif(_shellspace_library STREQUAL "cholmod" OR
         _shellspace_library STREQUAL "umfpack")
    string(TOUPPER ${_shellspace_library} _shellspace_upper)
    find_library(SHELLSPACE_${_shellspace_upper}_LIBRARY ${_shellspace_library}
      DOC "The ${_shellspace_upper} library (SuiteSparse)")
    find_path(SHELLSPACE_${_shellspace_upper}_INCLUDE_DIR ${_shellspace_library}.h
      PATH_SUFFIXES suitesparse
      DOC "The folder of ${_shellspace_library}.h (SuiteSparse)")
    if(NOT SHELLSPACE_${_shellspace_upper}_LIBRARY)
      list(APPEND shellspace_system_missing ${_shellspace_library})
      continue()
    endif()
    add_library(shellspace_system::${_shellspace_library} UNKNOWN IMPORTED)
    set_property(TARGET shellspace_system::${_shellspace_library} PROPERTY
      IMPORTED_LOCATION "${SHELLSPACE_${_shellspace_upper}_LIBRARY}")
    # Only the project compiles against the header; a consumer links the
    # library alone and does not need it.
    if(SHELLSPACE_${_shellspace_upper}_INCLUDE_DIR)
      set_property(TARGET shellspace_system::${_shellspace_library} PROPERTY
        INTERFACE_INCLUDE_DIRECTORIES
        "${SHELLSPACE_${_shellspace_upper}_INCLUDE_DIR}")
    endif()
  else()
    message(FATAL_ERROR "shellspaceSystemLibraries.cmake: no system library "
      "'${_shellspace_library}' (fast_blas, cholmod, umfpack)")
  endif()
endforeach()
unset(_shellspace_library)
unset(_shellspace_upper)
