// Our reader of Gmsh .msh files, versions 2.2 and 4.1, ASCII and binary (Gmsh's manual, "MSH
// file format"). Gmsh's own reader is left to .geo files for three reasons the mesh fuzzer
// (fuzz/fuzz_mesh.cpp) made plain: it runs any file that does not begin like a mesh as a Gmsh
// script (which may write files or start programs), it allocates whatever a count in the file
// asks for (a node count of 1e10 took minutes and gigabytes before failing), and it leaks the
// elements it read when it stops on an error. This reader checks every count against the bytes
// left before it allocates, names the section, node or element at fault, and reads nothing but
// the sections a body needs ($MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements; others
// are skipped).
#pragma once

#include <string>

#include "mesh_file_data.hpp"

namespace contactqp::detail {

// The contents of the .msh file at `path`. Throws InputError naming the file and what is wrong
// with it (a file that cannot be read, is not a .msh of version 2.2 or 4.1, ends early, holds a
// count its bytes cannot hold, a coordinate that is not a finite number, an element type
// contactqp does not know, a node defined twice).
MeshFileData read_msh_file(const std::string& path);

// The same for the file's bytes; `path` names it in messages.
MeshFileData parse_msh(const std::string& bytes, const std::string& path);

}  // namespace contactqp::detail
