// The libraries a run loads when it first needs them (docs/architecture.md, "Plugins"): Gmsh's
// (libcontactqp_gmsh.so, src/mesh/gmsh_plugin.hpp) and PETSc's with MPI
// (libcontactqp_petsc.so, src/petsc/petsc_plugin.hpp). Each plugin exports one extern "C"
// function returning its table of functions, whose first member is the table's ABI number, so
// that a plugin from another build of contactqp is refused rather than called with other
// struct layouts.
#pragma once

#include <string>

namespace contactqp::detail {

// Opens `file` (RTLD_NOW | RTLD_LOCAL: what the plugin links stays out of the global symbol
// scope; never closed: the libraries keep global state, and the sanitizers' leak report needs
// them mapped at exit) and returns what its `symbol` returns, checked to begin with `abi`. It
// is looked for in $CONTACTQP_PLUGIN_DIR, then beside the program or module that holds this
// library (the build tree's plugins/ folder, or the installed lib/contactqp/), then in the
// configured install prefix's lib/contactqp/. Throws std::runtime_error "<what> is unavailable:
// ..." naming where it looked and why each place failed.
const void* open_plugin(const char* file, const char* symbol, int abi, const std::string& what);

// The table type a plugin's entry returns; `Table` begins with `int abi`.
template <class Table>
const Table& open_plugin_table(const char* file, const char* symbol, int abi, const std::string& what) {
  return *static_cast<const Table*>(open_plugin(file, symbol, abi, what));
}

}  // namespace contactqp::detail
