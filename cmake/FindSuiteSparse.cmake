# Find the parts of SuiteSparse that Eigen's support modules use: UMFPACK and
# CHOLMOD (with AMD, COLAMD, CAMD, CCOLAMD, SuiteSparse_config).
#
# SuiteSparse >= 7 ships CMake configs (SuiteSparse::UMFPACK, SuiteSparse::CHOLMOD);
# SuiteSparse 5 on Debian 12 does not, so fall back to the headers in
# /usr/include/suitesparse and define the same imported targets.
# Defines: SuiteSparse_FOUND, SuiteSparse::UMFPACK, SuiteSparse::CHOLMOD.

find_package(UMFPACK CONFIG QUIET)
find_package(CHOLMOD CONFIG QUIET)
if(TARGET SuiteSparse::UMFPACK AND TARGET SuiteSparse::CHOLMOD)
  set(SuiteSparse_FOUND TRUE)
  return()
endif()

find_path(SuiteSparse_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
foreach(lib umfpack cholmod amd colamd camd ccolamd suitesparseconfig)
  string(TOUPPER ${lib} LIB)
  find_library(SuiteSparse_${LIB}_LIBRARY ${lib})
endforeach()
find_package(BLAS QUIET)
find_package(LAPACK QUIET)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS SuiteSparse_INCLUDE_DIR SuiteSparse_UMFPACK_LIBRARY SuiteSparse_CHOLMOD_LIBRARY
                SuiteSparse_AMD_LIBRARY SuiteSparse_COLAMD_LIBRARY SuiteSparse_SUITESPARSECONFIG_LIBRARY)

if(SuiteSparse_FOUND)
  set(_ss_common ${SuiteSparse_AMD_LIBRARY} ${SuiteSparse_COLAMD_LIBRARY}
                 ${SuiteSparse_SUITESPARSECONFIG_LIBRARY})
  if(SuiteSparse_CAMD_LIBRARY)
    list(APPEND _ss_common ${SuiteSparse_CAMD_LIBRARY})
  endif()
  if(SuiteSparse_CCOLAMD_LIBRARY)
    list(APPEND _ss_common ${SuiteSparse_CCOLAMD_LIBRARY})
  endif()
  if(LAPACK_FOUND)
    list(APPEND _ss_common ${LAPACK_LIBRARIES})
  endif()
  if(BLAS_FOUND)
    list(APPEND _ss_common ${BLAS_LIBRARIES})
  endif()
  if(NOT TARGET SuiteSparse::CHOLMOD)
    add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
      IMPORTED_LOCATION "${SuiteSparse_CHOLMOD_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_ss_common}")
  endif()
  if(NOT TARGET SuiteSparse::UMFPACK)
    add_library(SuiteSparse::UMFPACK UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::UMFPACK PROPERTIES
      IMPORTED_LOCATION "${SuiteSparse_UMFPACK_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "SuiteSparse::CHOLMOD;${_ss_common}")
  endif()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
