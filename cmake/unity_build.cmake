# Unity builds: each target's sources compiled in batches of 8 files, one compiler run per batch,
# so the headers (Eigen, Catch, nlohmann-json) are parsed and their templates instantiated once
# per batch instead of once per file. CI builds from empty directories with no compiler cache,
# twice (Release, then sanitized), and most of its time is compiling (tools/run-tests.sh).
#
# Off by default when a compiler launcher is set (-DCMAKE_CXX_COMPILER_LAUNCHER=ccache): a
# developer's edit of one file would recompile its whole batch, and a cached rebuild costs less.
# A file's names at namespace scope are then seen by the other files of its batch, so two files
# of one target must not define the same name, even in an anonymous namespace; the builds
# without unity (any build with ccache, or -DCONTACTQP_UNITY_BUILD=OFF) tell a file that forgets
# an #include it needs and compiles only after a neighbour in its batch.
# The default is the precompiled headers' (included before this file, which sets it).
option(CONTACTQP_UNITY_BUILD "Compile each target's sources in batches (faster builds without ccache)"
       ${contactqp_precompile_default})
if(CONTACTQP_UNITY_BUILD)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)
endif()
