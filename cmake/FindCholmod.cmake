# CHOLMOD (SuiteSparse) ships neither a CMake config nor a .pc file on Debian bookworm:
# find the header and the library and wrap them in the imported target Cholmod::Cholmod.
# Linking libcholmod alone pulls AMD, COLAMD, CAMD, CCOLAMD, METIS and BLAS/LAPACK
# (OpenBLAS once libopenblas-dev is installed).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
if(NOT TARGET Cholmod::Cholmod)
  add_library(Cholmod::Cholmod UNKNOWN IMPORTED)
  set_target_properties(Cholmod::Cholmod PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()
message(STATUS "CHOLMOD: ${CHOLMOD_LIBRARY}")
