# `cmake --install build --prefix P`: the libraries, the public headers, a CMake package
# (find_package(contactqp) -> contactqp::contactqp), contactqp.pc, and the CLI. The Python
# module installs itself (python/CMakeLists.txt).
#
# The libraries are static archives, so their private dependencies (CHOLMOD, LAPACK, NLopt)
# are link dependencies of whoever links them: contactqpConfig.cmake finds them again the
# way this build did, with the find module installed beside it. Gmsh is not one: the library
# opens the Gmsh plugin, installed in lib/contactqp/, when a run meshes with it, nor is PETSc:
# its plugin, beside Gmsh's, is opened by the first run that uses it, and Ipopt's likewise.
include(CMakePackageConfigHelpers)
set(CONTACTQP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/contactqp)

# Where PETSc is built in, the room's plugin-free part and its calls to the PETSc plugin
# (installed in lib/contactqp/ beside Gmsh's); without it, the room that says so.
if(CONTACTQP_WITH_PETSC)
  set(installed_petsc cqp_petsc_plugin_calls)
else()
  set(installed_petsc cqp_petsc_plugin_calls cqp_petsc)
endif()
install(TARGETS cqp_qp cqp_solvers cqp_fe cqp_run ${installed_petsc} contactqp_library
        EXPORT contactqpTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS contactqp RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/contactqp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp")
install(EXPORT contactqpTargets NAMESPACE contactqp:: DESTINATION ${CONTACTQP_CMAKE_DIR})

configure_package_config_file(cmake/contactqpConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/contactqpConfig.cmake
                              INSTALL_DESTINATION ${CONTACTQP_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/contactqpConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/contactqpConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/contactqpConfigVersion.cmake
              cmake/FindCholmod.cmake
        DESTINATION ${CONTACTQP_CMAKE_DIR})

# pkg-config: the archives in link order, then what they need (static libraries carry no
# dependency list of their own).
set(CONTACTQP_PC_REQUIRES "eigen3")
# Neither PETSc and MPI nor Ipopt: their plugins, in lib/contactqp/, link them.
set(CONTACTQP_PC_PETSC "-lcqp_petsc")
if(CONTACTQP_WITH_PETSC)
  set(CONTACTQP_PC_PETSC "-lcqp_petsc_plugin_calls")
endif()
if(CONTACTQP_HAVE_NLOPT)
  string(APPEND CONTACTQP_PC_REQUIRES " nlopt")
endif()
# Every library's list of built-in registrations (cmake/builtins.cmake) is kept in the link the
# way the CMake package keeps it: -Wl,--undefined=<its symbol> before the archives.
get_property(anchors GLOBAL PROPERTY CONTACTQP_BUILTIN_ANCHORS)
set(CONTACTQP_PC_KEEP "")
foreach(anchor IN LISTS anchors)
  if(CONTACTQP_WITH_PETSC AND anchor STREQUAL "contactqp_builtins_cqp_petsc")
    continue()  # the room linked whole is not installed: the PETSc plugin holds it
  endif()
  string(APPEND CONTACTQP_PC_KEEP " -Wl,--undefined=${anchor}")
endforeach()
# Relocatable: the prefix is found from the .pc file's own place, so `--prefix P` at install
# time works (libdir is lib, or lib/<multiarch> under /usr).
string(REGEX REPLACE "[^/]+" ".." CONTACTQP_PC_TO_PREFIX "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
configure_file(cmake/contactqp.pc.in ${CMAKE_CURRENT_BINARY_DIR}/contactqp.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/contactqp.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
