// Our .msh reader (src/mesh/msh_reader.cpp) against Gmsh's: every mesh Gmsh writes — 2D and 3D,
// linear and quadratic, with boundaries, regions and named points — in each of the four formats
// (2.2 and 4.1, ASCII and binary) reads to the very Mesh Gmsh's own reader gave; and every
// prefix of a small file, and files with counts that lie, are an InputError, never a crash or an
// allocation the file cannot back.
#include <gmsh.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "contactqp/errors.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_file_data.hpp"
#include "mesh/msh_reader.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// What Gmsh's own reader made of a .msh file: the path contactqp took before its reader.
Mesh read_with_gmsh(const std::string& path) {
  detail::GmshSession session;
  gmsh::open(path);
  detail::throw_if_gmsh_failed();
  return detail::mesh_from_gmsh();
}

void check_same(const Mesh& ours, const Mesh& gmsh) {
  REQUIRE(ours.dim == gmsh.dim);
  REQUIRE(ours.order == gmsh.order);
  REQUIRE(ours.nodes.size() == gmsh.nodes.size());
  for (size_t i = 0; i < ours.nodes.size(); ++i) REQUIRE(ours.nodes[i] == gmsh.nodes[i]);  // to the bit
  CHECK(ours.elements == gmsh.elements);
  REQUIRE(ours.boundaries.size() == gmsh.boundaries.size());
  for (const auto& [name, faces] : gmsh.boundaries) {
    CAPTURE(name);
    REQUIRE(ours.boundaries.count(name) == 1);
    const auto& mine = ours.boundaries.at(name);
    REQUIRE(mine.size() == faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
      CHECK(mine[f].n_nodes == faces[f].n_nodes);
      for (int k = 0; k < faces[f].n_nodes; ++k) CHECK(mine[f].nodes[k] == faces[f].nodes[k]);
    }
  }
  CHECK(ours.regions == gmsh.regions);
  CHECK(ours.points == gmsh.points);
}

// Meshes `geo` with Gmsh (at `order`) and saves it in the four formats; returns their paths.
std::vector<std::string> saved_in_every_format(const std::string& geo, int order, const TemporaryDirectory& directory,
                                               const std::string& stem) {
  std::vector<std::string> paths;
  detail::GmshSession session;
  gmsh::open(geo);
  gmsh::option::setNumber("Mesh.ElementOrder", order);
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  gmsh::model::mesh::generate(volumes.empty() ? 2 : 3);
  for (double version : {2.2, 4.1})
    for (int binary : {0, 1}) {
      const std::string path =
          directory.path(stem + "-" + std::to_string(static_cast<int>(version * 10)) + (binary ? "b" : "a") + ".msh");
      gmsh::option::setNumber("Mesh.MshFileVersion", version);
      gmsh::option::setNumber("Mesh.Binary", binary);
      gmsh::write(path);
      paths.push_back(path);
    }
  return paths;
}

}  // namespace

TEST_CASE("our .msh reader gives the mesh Gmsh's gave, in each format", "[unit][gmsh][msh]") {
  TemporaryDirectory directory;
  struct Source {
    std::string geo;
    int order;
  };
  for (const Source& source :
       {Source{"scenes/hertz_disc.geo", 1}, Source{"scenes/hertz_disc.geo", 2}, Source{"scenes/strip.geo", 2},
        Source{"scenes/pin.geo", 1}, Source{"scenes/pin.geo", 2}}) {
    CAPTURE(source.geo, source.order);
    for (const std::string& path : saved_in_every_format(source_path(source.geo), source.order, directory, "mesh")) {
      CAPTURE(path);
      check_same(detail::read_gmsh_file({path}), read_with_gmsh(path));
    }
  }
  // And contactqp's own writer (4.1 binary, named points and boundaries of a generated body).
  const std::string written = directory.path("sphere.msh");
  REQUIRE(run_cli("mesh " + source_path("scenes/hertz-sphere.json") + " -o " + written).exit_status == 0);
  check_same(detail::read_gmsh_file({written}), read_with_gmsh(written));
}

namespace {

const std::string kSquare22 = kUnitSquareMsh;

const std::string kSquare41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "body"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 1 0
1 0 0 0 1 1 0 1 2 0
$EndEntities
$Nodes
2 4 1 4
1 1 0 2
1
2
0 0 0
1 0 0
2 1 0 2
3
4
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 1 2
2 1 2 2
2 1 2 3
3 1 3 4
$EndElements
)";

}  // namespace

TEST_CASE("every prefix of a .msh file is an InputError naming it, never a crash", "[unit][msh]") {
  for (const std::string& text : {kSquare22, kSquare41}) {
    const Mesh whole = detail::mesh_from_file_data(detail::parse_msh(text, "square.msh"));
    CHECK(whole.n_elements() == 2);
    CHECK(whole.boundaries.at("bottom").size() == 1);
    for (size_t n = 0; n + 1 < text.size(); ++n) {
      CAPTURE(text.substr(0, n));
      try {
        detail::mesh_from_file_data(detail::parse_msh(text.substr(0, n), "square.msh"));
        // A prefix that ends inside the last section's end marker may still hold the whole mesh.
        CHECK(n > text.size() - 16);
      } catch (const InputError& error) {
        CHECK(error.field() == "square.msh");
      } catch (const std::runtime_error&) {
        // The checks of the mesh (read_gmsh_file names the file): fine too.
      }
    }
  }
}

TEST_CASE("counts a .msh file cannot back are refused before anything is allocated", "[unit][msh]") {
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  struct Case {
    std::string text, names;
  };
  const Case cases[] = {
      {replaced(kSquare22, "$Nodes\n4\n", "$Nodes\n4000000000000\n"), "declares 4000000000000 nodes"},
      {replaced(kSquare22, "$Elements\n6\n", "$Elements\n999999999999999\n"), "declares 999999999999999 elements"},
      {replaced(kSquare22, "$Nodes\n4\n", "$Nodes\n-4\n"), "the number of nodes"},
      {replaced(kSquare41, "2 4 1 4\n", "2 4000000000000 1 4\n"), "declares 4000000000000 nodes"},
      {replaced(kSquare41, "2 3 1 3\n", "2 3 1 3\n1 1 1 9999999999\n"), "declares 9999999999 elements"},
      {replaced(kSquare22, "2 1 0 0", "2 nan 0 0"), "not a finite number"},
      {replaced(kSquare22, "2 1 0 0", "2 1e999 0 0"), "2"},
      {replaced(kSquare22, "3 1 1 0", "2 1 1 0"), "defines node 2 twice"},
      {replaced(kSquare22, "5 2 2 5 1 1 2 3", "5 99 2 5 1 1 2 3"), "Gmsh element type 99"},
      {replaced(kSquare22, "2.2 0 8", "2.2 0 4"), "has the format line \"2.2 0 4\""},
      {"Merge \"other.msh\";\n", "is not a Gmsh mesh file"},
      {replaced(kSquare22, "$Nodes", "$Nodez"), "has a $Nodez section without $EndNodez"},
      {replaced(replaced(kSquare22, "$Nodes", "$Nodez"), "$EndNodes", "$EndNodez"), "has no $Nodes section"},
      {replaced(kSquare22, "$EndNodes", "$EndNode"), "$EndNodes"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.text);
    CHECK_THROWS_WITH(detail::parse_msh(c.text, "bad.msh"),
                      Catch::Matchers::Contains(c.names) && Catch::Matchers::StartsWith("bad.msh"));
  }
}
