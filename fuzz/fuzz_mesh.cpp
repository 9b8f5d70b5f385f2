// libFuzzer target: mesh files. The bytes are read as a scene's "shape": "mesh" body reads a .msh
// file: our reader of the 2.2 and 4.1 formats, ASCII and binary (src/mesh/msh_reader.cpp), then
// the checks every body passes — element types and order, nodes in the plane, orientation,
// degenerate and tangled elements, physical groups and their names (mesh_from_file_data). The
// result must be a Mesh, an InputError naming the file, or the checks' std::runtime_error
// (which read_gmsh_file turns into an InputError naming the file); anything else — another
// exception, a crash, a hang, an allocation beyond -rss_limit_mb, a sanitizer report — is a
// finding. Seeds: tools/mesh_corpus.py (the shipped scenes' meshes, in the four formats).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "contactqp/errors.hpp"
#include "mesh/mesh_file_data.hpp"
#include "mesh/msh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  contactqp::detail::MeshFileData contents;
  try {
    contents = contactqp::detail::parse_msh(bytes, "fuzz.msh");
  } catch (const contactqp::InputError&) {
    return 0;  // bad input, reported as it should be
  }
  try {
    contactqp::detail::mesh_from_file_data(contents);
  } catch (const contactqp::InputError&) {
    // a name or value the checks refuse
  } catch (const std::runtime_error&) {
    // a mesh contactqp cannot use, which read_gmsh_file reports naming the file
  }
  return 0;
}
