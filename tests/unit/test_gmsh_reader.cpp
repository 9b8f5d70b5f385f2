// Gmsh files: .msh 2.2 and 4.1 written by the gmsh program from the repository's .geo, read
// back with their physical names; hand-written files with defects are errors naming the file
// and the element.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>

#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "mesh/gmsh_reader.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;
using detail::read_gmsh_file;

namespace {

// Runs the gmsh program (Debian's gmsh package) on a .geo of the repository.
std::string gmsh_file(const TemporaryDirectory& directory, const std::string& geo, const std::string& format,
                      int order) {
  const std::string out = directory.path(format + "-" + std::to_string(order) + ".msh");
  const std::string command = "gmsh " + source_path(geo) + " -2 -order " + std::to_string(order) + " -format " +
                              format + " -o " + out + " >/dev/null 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  return out;
}

// A unit square of two triangles (1 2 3) and (1 3 4), a bottom edge, physical names, and
// `extra` appended to the elements.
std::string square_msh22(const std::string& second_triangle, const std::string& extra_nodes = "",
                         const std::string& extra_elements = "", int n_extra_nodes = 0, int n_extra_elements = 0) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"bottom\"\n2 2 \"body\"\n$EndPhysicalNames\n"
         "$Nodes\n" +
         std::to_string(4 + n_extra_nodes) + "\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n" + extra_nodes +
         "$EndNodes\n$Elements\n" + std::to_string(3 + n_extra_elements) +
         "\n1 1 2 1 1 1 2\n2 2 2 2 1 1 2 3\n3 2 2 2 1 " + second_triangle + "\n" + extra_elements + "$EndElements\n";
}

std::string write(const TemporaryDirectory& directory, const std::string& name, const std::string& text) {
  const std::string path = directory.path(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("msh 2.2 and 4.1, orders 1 and 2, read the same mesh with its physical names", "[unit][gmsh]") {
  TemporaryDirectory directory;
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  const Mesh v22 = read_gmsh_file({gmsh_file(directory, "scenes/hertz_disc.geo", "msh22", order)});
  const Mesh v41 = read_gmsh_file({gmsh_file(directory, "scenes/hertz_disc.geo", "msh41", order)});
  const Mesh geo = read_gmsh_file({source_path("scenes/hertz_disc.geo"), order});
  for (const Mesh* mesh : {&v22, &v41, &geo}) {
    CHECK(mesh->order == order);
    CHECK(mesh->n_nodes() == v41.n_nodes());
    CHECK(mesh->n_elements() == v41.n_elements());
    CHECK(mesh->elements == v41.elements);
    REQUIRE(mesh->boundaries.count("arc"));
    REQUIRE(mesh->boundaries.count("top"));
    CHECK(mesh->regions.at("body").size() == static_cast<size_t>(mesh->n_elements()));
    for (int e = 0; e < mesh->n_elements(); ++e) CHECK(element_area(*mesh, e) > 0);
  }
  // Gmsh places every node of the arc, mid-side ones too, on the circle.
  for (int node : boundary_nodes(v22, "arc"))
    CHECK((v22.nodes[node].head<2>() - Eigen::Vector2d(0, 1)).norm() == Approx(1.0).epsilon(1e-12));
  for (int k = 0; k < v22.n_nodes(); ++k) CHECK((v22.nodes[k] - v41.nodes[k]).norm() < 1e-12);
}

TEST_CASE("physical points name nodes, and unnamed groups go by their tag", "[unit][gmsh]") {
  TemporaryDirectory directory;
  const std::string geo = write(directory, "points.geo", R"(
Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {0, 1, 0, 0.3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Physical Curve(7) = {1}; Physical Point("tip") = {2}; Physical Surface("body") = {1};
)");
  const Mesh mesh = read_gmsh_file({geo});
  REQUIRE(mesh.points.count("tip"));
  CHECK(mesh.nodes[mesh.points.at("tip").front()].isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(mesh.boundaries.count("7"));
}

TEST_CASE("a clockwise surface is turned as a whole, a single clockwise element is an error", "[unit][gmsh]") {
  TemporaryDirectory directory;
  SECTION("both triangles clockwise: a consistently oriented mesh") {
    const Mesh mesh = read_gmsh_file(
        {write(directory, "cw.msh",
               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n"
               "$Elements\n2\n1 2 2 1 1 1 3 2\n2 2 2 1 1 1 4 3\n$EndElements\n")});
    for (int e = 0; e < mesh.n_elements(); ++e) CHECK(element_area(mesh, e) > 0);
  }
  SECTION("one of three clockwise") {
    const std::string path =
        write(directory, "inverted.msh", square_msh22("1 4 3", "5 2 1 0\n", "4 2 2 2 1 2 5 3\n", 1, 1));
    CHECK_THROWS_WITH(read_gmsh_file({path}),
                      Catch::Matchers::Contains("inverted.msh") && Catch::Matchers::Contains("element 3 is inverted"));
  }
}

TEST_CASE("defective or unsupported files are errors naming the file", "[unit][gmsh]") {
  TemporaryDirectory directory;
  struct Case {
    std::string name, text, says;
  };
  const Case cases[] = {
      {"degenerate.msh", square_msh22("1 3 4", "5 2 0 0\n", "4 2 2 2 1 2 1 5\n", 1, 1), "element 4 is degenerate"},
      {"quads.msh", square_msh22("1 3 4", "", "4 3 2 2 1 1 2 3 4\n", 0, 1), "4-node quadrangle elements"},
      {"garbage.msh", "this is not a mesh\n", "is not a Gmsh mesh file"},
      {"truncated.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n",
       "declares 4 nodes, more than its remaining"},
      {"empty.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", "has no $Nodes section"},
      {"lifted.msh", square_msh22("1 3 4").replace(square_msh22("1 3 4").find("3 1 1 0"), 7, "3 1 1 5"), "z = "},
      {"bad.geo", "Point(1) = {0, 0, 0\n", "could not be meshed by Gmsh"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const std::string path = write(directory, c.name, c.text);
    CHECK_THROWS_AS(read_gmsh_file({path}), InputError);
    CHECK_THROWS_WITH(read_gmsh_file({path}), Catch::Matchers::Contains(c.name) && Catch::Matchers::Contains(c.says));
  }
  CHECK_THROWS_WITH(read_gmsh_file({directory.path("missing.msh")}), Catch::Matchers::Contains("missing.msh"));
}

TEST_CASE("a .geo is meshed with the scene's order and size factor", "[unit][gmsh]") {
  const Mesh coarse = read_gmsh_file({source_path("scenes/strip.geo"), 0, 2.0});
  const Mesh fine = read_gmsh_file({source_path("scenes/strip.geo"), 2, 1.0});
  CHECK(coarse.order == 1);
  CHECK(fine.order == 2);
  CHECK(fine.n_elements() > 3 * coarse.n_elements());
  for (const char* name : {"bottom", "punch", "top", "ends"}) CHECK(fine.boundaries.count(name));
  CHECK(fine.regions.count("strip"));
}
