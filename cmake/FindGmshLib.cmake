# Gmsh's C++ API (Debian's libgmsh-dev) has no CMake config: wrap header and library in
# the imported target Gmsh::Gmsh. It meshes the generated geometries (half disc, ...).
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
if(NOT TARGET Gmsh::Gmsh)
  add_library(Gmsh::Gmsh UNKNOWN IMPORTED)
  set_target_properties(Gmsh::Gmsh PROPERTIES
    IMPORTED_LOCATION "${GMSH_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${GMSH_INCLUDE_DIR}")
endif()
message(STATUS "Gmsh: ${GMSH_LIBRARY}")
