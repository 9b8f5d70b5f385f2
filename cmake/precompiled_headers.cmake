# contactqp_precompile_headers(<target> [<header>...]): the given headers and Eigen's parsed
# once for <target> instead of once per source file. CI builds from empty directories
# with no compiler cache, and most of its time is compiling (tools/run-tests.sh); only targets
# with many Eigen-heavy files use this, since each precompiled header costs a compile of its own.
#
# Off by default when a compiler launcher is set (-DCMAKE_CXX_COMPILER_LAUNCHER=ccache): ccache
# does not cache a file compiled with a precompiled header unless it is told to be sloppy about
# it (sloppiness = pch_defines,time_macros), and a cached rebuild costs less than the headers.
# A file that forgets an #include it needs compiles with the precompiled header and not
# without; the builds without it (any build with ccache, or -DCONTACTQP_PRECOMPILE_HEADERS=OFF)
# tell.
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(contactqp_precompile_default OFF)
else()
  set(contactqp_precompile_default ON)
endif()
option(CONTACTQP_PRECOMPILE_HEADERS "Precompile Eigen's headers for the larger targets (faster builds without ccache)"
       ${contactqp_precompile_default})

function(contactqp_precompile_headers target)
  if(CONTACTQP_PRECOMPILE_HEADERS)
    # The given headers first: pybind11's must come before any standard header (Python.h).
    target_precompile_headers(${target} PRIVATE ${ARGN} <Eigen/Core> <Eigen/SparseCore> <functional> <map> <memory>
                                                <string> <vector>)
  endif()
endfunction()
