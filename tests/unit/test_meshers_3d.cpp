// The 3D side of the Gmsh meshers and reader: the generated hemisphere and box against their
// exact geometry (volume, faces on the sphere and on the planes, outward normals), Gmsh's
// 10-node tetrahedron order against Gmsh's own reference nodes, .msh and .geo files holding
// tetrahedra, the defects that are errors, and the element-count estimates.
#include <gmsh.h>

#include <unistd.h>
#include <Eigen/Dense>  // determinant()
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "contactqp/errors.hpp"
#include "contactqp/mesh.hpp"
#include "mesh/box_mesher.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/half_disc_mesher.hpp"
#include "mesh/hemisphere_mesher.hpp"
#include "mesh/shape_functions.hpp"
#include "mesh_volume.hpp"
#include "qp/pi.hpp"

using namespace contactqp;
using namespace contactqp::detail;
using contactqp::testing::check_boundaries_tile_surface;
using contactqp::testing::isoparametric_volume;
using contactqp::testing::total_volume;

namespace {

// A fresh directory under the system's temporary one, removed with its files.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    static int count = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("contactqp-meshers-3d-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string file = (path_ / name).string();
    std::ofstream(file) << text;
    return file;
  }

 private:
  std::filesystem::path path_;
};

void check_no_defect(const Mesh& mesh) {
  const double largest = largest_element_measure(mesh);
  int defective = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) defective += !element_defect(mesh, e, largest).empty();
  CHECK(defective == 0);
}

// Mean edge length of the tetrahedra whose centroid satisfies `near`.
template <class Near>
double mean_edge(const Mesh& mesh, Near near) {
  double sum = 0;
  int count = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    const Eigen::Vector3d centroid = (mesh.nodes[v[0]] + mesh.nodes[v[1]] + mesh.nodes[v[2]] + mesh.nodes[v[3]]) / 4;
    if (!near(centroid)) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) sum += (mesh.nodes[v[i]] - mesh.nodes[v[j]]).norm(), ++count;
  }
  REQUIRE(count > 0);
  return sum / count;
}

// Gmsh 2.2 .msh text: nodes "tag x y z" lines, elements "tag type 2 physical elementary nodes..." lines.
std::string msh22(const std::vector<std::string>& nodes, const std::vector<std::string>& elements) {
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
  for (const auto& line : nodes) text += line + "\n";
  text += "$EndNodes\n$Elements\n" + std::to_string(elements.size()) + "\n";
  for (const auto& line : elements) text += line + "\n";
  return text + "$EndElements\n";
}

// The reference 10-node tetrahedron's nodes in Gmsh's order (mid-edges 01, 12, 02, 03, 23, 13).
const std::vector<std::string> kTet10Nodes = {"1 0 0 0",     "2 1 0 0",   "3 0 1 0",   "4 0 0 1",     "5 0.5 0 0",
                                              "6 0.5 0.5 0", "7 0 0.5 0", "8 0 0 0.5", "9 0 0.5 0.5", "10 0.5 0 0.5"};

}  // namespace

TEST_CASE("Gmsh's reference nodes: its 10-node tetrahedron reordered is ours and its 6-node triangle is ours",
          "[unit][gmsh][3d]") {
  GmshSession session;
  std::string name;
  int dim, order, n_nodes, n_primary;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(11, name, dim, order, n_nodes, local, n_primary);
  REQUIRE(n_nodes == 10);
  REQUIRE(dim == 3);
  // Our node i is Gmsh's node gmsh_of[i] (the reader's permutation: 13 and 23 are swapped).
  const int gmsh_of[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  for (int i = 0; i < 10; ++i) {
    CAPTURE(i);
    const Eigen::Vector3d gmsh(local[3 * gmsh_of[i]], local[3 * gmsh_of[i] + 1], local[3 * gmsh_of[i] + 2]);
    CHECK((gmsh - reference_tetrahedron_node(i)).norm() < 1e-15);
  }
  local.clear();  // Gmsh appends to it
  gmsh::model::mesh::getElementProperties(9, name, dim, order, n_nodes, local, n_primary);
  REQUIRE(n_nodes == 6);
  REQUIRE(local.size() == 12);                                                         // dim (2) coordinates per node
  const double ours[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};  // v0 v1 v2 m01 m12 m20
  for (int i = 0; i < 6; ++i) {
    CHECK(local[2 * i] == ours[i][0]);
    CHECK(local[2 * i + 1] == ours[i][1]);
  }
}

TEST_CASE("a 10-node tetrahedron read from a .msh has our node order and is turned positive when it is not",
          "[unit][gmsh][3d]") {
  ScratchDirectory directory;
  const bool negative = GENERATE(false, true);
  CAPTURE(negative);
  // Gmsh's order; the negative one swaps vertices 1 and 2 (and with them the mid-edges 02 ↔ 01, 13 ↔ 23).
  const std::string element = negative ? "1 11 2 1 1 1 3 2 4 7 6 5 8 10 9" : "1 11 2 1 1 1 2 3 4 5 6 7 8 9 10";
  const std::string face = negative ? "2 9 2 2 1 1 3 2 7 6 5" : "2 9 2 2 1 1 2 3 5 6 7";  // the face z = 0
  std::string text = msh22(kTet10Nodes, {element, face});
  text.insert(text.find("$Nodes"), "$PhysicalNames\n2\n2 2 \"bottom\"\n3 1 \"body\"\n$EndPhysicalNames\n");
  const Mesh mesh = read_gmsh_file({directory.write("tet10.msh", text)});
  REQUIRE(mesh.dim == 3);
  REQUIRE(mesh.order == 2);
  REQUIRE(mesh.n_elements() == 1);
  CHECK(element_measure(mesh, 0) == Approx(1.0 / 6));
  check_no_defect(mesh);
  // The element's nodes are the reference nodes in our order: reordered from Gmsh's and, for
  // the negative one, flipped back (vertices 1 ↔ 2 with their mid-edges) to the positive one.
  const int* v = mesh.element(0);
  for (int i = 0; i < 10; ++i) {
    CAPTURE(i);
    CHECK((mesh.nodes[v[i]] - reference_tetrahedron_node(i)).norm() < 1e-15);
  }
  // The face is oriented outwards (−z) and its mid-sides follow its vertices.
  const BoundaryFace& bottom = mesh.boundaries.at("bottom").at(0);
  REQUIRE(bottom.n_nodes == 6);
  CHECK(face_normal(mesh, bottom).isApprox(Eigen::Vector3d(0, 0, -1)));
  for (int k = 0; k < 3; ++k)
    CHECK(
        (mesh.nodes[bottom.nodes[3 + k]] - 0.5 * (mesh.nodes[bottom.nodes[k]] + mesh.nodes[bottom.nodes[(k + 1) % 3]]))
            .norm() < 1e-15);
  CHECK(mesh.regions.at("body") == std::vector<int>{0});
}

TEST_CASE("the quarter hemisphere: volume and faces on the sphere and the planes with outward normals",
          "[unit][gmsh][3d]") {
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  HemisphereMeshRequest request;
  request.radius = 2.5;  // meshed in units of R and scaled: every check below scales with R
  request.symmetry = true;
  request.size = 0.5;
  request.contact_size = 0.05;
  request.grading = 0.3;
  request.fine_radius = 0.5;
  request.order = order;
  const Mesh mesh = mesh_hemisphere(request);
  const double R = request.radius;
  REQUIRE(mesh.dim == 3);
  REQUIRE(mesh.order == order);
  CHECK(mesh.type() == (order == 1 ? ElementType::Tet4 : ElementType::Tet10));
  check_no_defect(mesh);

  // The exact quarter of the half ball is (2/3) π R³ / 4. The straight-sided tetrahedra are
  // inscribed (their vertices on the sphere): below it by about the chord error (h/R)²/8 of
  // the far size h = 0.2 R; the curved 10-node ones are far closer.
  const double exact = 2 * kPi * R * R * R / 3 / 4;
  const double straight = total_volume(mesh);
  CHECK(straight < exact);
  CHECK(straight > exact * (1 - 0.02));
  if (order == 2) CHECK(std::abs(isoparametric_volume(mesh) - exact) < 1e-3 * exact);

  const std::set<std::string> names = {"surface", "top", "symmetry_x", "symmetry_y"};
  std::set<std::string> found;
  for (const auto& [name, faces] : mesh.boundaries) found.insert(name);
  CHECK(found == names);
  check_boundaries_tile_surface(mesh);

  const Eigen::Vector3d centre(0, 0, R);
  for (int node : boundary_nodes(mesh, "surface")) CHECK(std::abs((mesh.nodes[node] - centre).norm() - R) < 1e-9 * R);
  for (int node : boundary_nodes(mesh, "top")) CHECK(std::abs(mesh.nodes[node].z() - R) < 1e-12 * R);
  for (int node : boundary_nodes(mesh, "symmetry_x")) CHECK(std::abs(mesh.nodes[node].x()) < 1e-12 * R);
  for (int node : boundary_nodes(mesh, "symmetry_y")) CHECK(std::abs(mesh.nodes[node].y()) < 1e-12 * R);
  for (const auto& node : mesh.nodes) {
    CHECK(node.x() >= -1e-12 * R);
    CHECK(node.y() >= -1e-12 * R);
  }

  for (const BoundaryFace& face : mesh.boundaries.at("top"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));
  for (const BoundaryFace& face : mesh.boundaries.at("symmetry_x"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-9));
  for (const BoundaryFace& face : mesh.boundaries.at("symmetry_y"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(0, -1, 0), 1e-9));
  for (const BoundaryFace& face : mesh.boundaries.at("surface")) {
    const Eigen::Vector3d middle =
        (mesh.nodes[face.nodes[0]] + mesh.nodes[face.nodes[1]] + mesh.nodes[face.nodes[2]]) / 3;
    CHECK(face_normal(mesh, face).dot((middle - centre).normalized()) > 0.9);
    CHECK(face.n_nodes == (order == 1 ? 3 : 6));
  }

  // The graded size: contact_size near the lowest point, the far size at the top.
  const double near = mean_edge(mesh, [&](const Eigen::Vector3d& x) { return x.norm() < 0.5 * request.fine_radius; });
  const double far = mean_edge(mesh, [&](const Eigen::Vector3d& x) { return x.z() > 0.8 * R; });
  CHECK(near > 0.7 * request.contact_size);
  CHECK(near < 1.6 * request.contact_size);
  CHECK(far > 0.5 * request.size);
  CHECK(far < 1.6 * request.size);

  if (order == 2) {
    // Interior mid-edge nodes sit at their edge's midpoint, in our order (01, 12, 20, 03, 13, 23).
    const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    const std::vector<int> on_surface = boundary_nodes(mesh, "surface");
    int interior = 0;
    for (int e = 0; e < mesh.n_elements(); ++e) {
      const int* v = mesh.element(e);
      for (int k = 0; k < 6; ++k) {
        if (std::binary_search(on_surface.begin(), on_surface.end(), v[4 + k])) continue;  // curved: on the sphere
        ++interior;
        const Eigen::Vector3d middle = 0.5 * (mesh.nodes[v[edges[k][0]]] + mesh.nodes[v[edges[k][1]]]);
        CHECK((mesh.nodes[v[4 + k]] - middle).norm() < 1e-9 * R);
      }
    }
    CHECK(interior > 0);
  }
}

TEST_CASE("the whole hemisphere has a spherical surface and a flat top only", "[unit][gmsh][3d]") {
  HemisphereMeshRequest request;
  request.size = 0.3;
  request.contact_size = 0.05;
  request.grading = 0.3;
  request.fine_radius = 0.2;
  const Mesh mesh = mesh_hemisphere(request);
  check_no_defect(mesh);
  CHECK(mesh.boundaries.size() == 2);
  check_boundaries_tile_surface(mesh);
  const double exact = 2 * kPi / 3;
  CHECK(total_volume(mesh) < exact);
  CHECK(total_volume(mesh) > exact * (1 - 0.03));
  double lowest = 1;
  for (const auto& node : mesh.nodes) lowest = std::min(lowest, node.z());
  CHECK(lowest == Approx(0.0).margin(1e-12));  // the lowest point is a node: where contact starts
}

TEST_CASE("the box: exact volume and six faces on their planes with outward normals and refined on the disc",
          "[unit][gmsh][3d]") {
  const bool symmetry = GENERATE(false, true);
  const int order = GENERATE(1, 2);
  CAPTURE(symmetry, order);
  BoxMeshRequest request;
  request.width = 8;
  request.depth = 6;
  request.height = 4;
  request.symmetry = symmetry;
  request.size = 1.0;
  request.contact_size = 0.1;
  request.grading = 0.3;
  request.fine_radius = 0.5;
  request.fine_centre = symmetry ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(0.5, -0.75);  // negative: see box_mesher.cpp
  request.order = order;
  const Mesh mesh = mesh_box(request);
  REQUIRE(mesh.dim == 3);
  REQUIRE(mesh.order == order);
  check_no_defect(mesh);
  const double volume = (symmetry ? 0.25 : 1.0) * request.width * request.depth * request.height;
  CHECK(total_volume(mesh) == Approx(volume).epsilon(1e-12));
  check_boundaries_tile_surface(mesh);

  struct Plane {
    const char* name;
    int axis;
    double at;
    Eigen::Vector3d normal;
  };
  const double w = request.width / 2, d = request.depth / 2;
  const Plane planes[] = {{"bottom", 2, 0.0, {0, 0, -1}},
                          {"top", 2, request.height, {0, 0, 1}},
                          {symmetry ? "symmetry_x" : "left", 0, symmetry ? 0.0 : -w, {-1, 0, 0}},
                          {"right", 0, w, {1, 0, 0}},
                          {symmetry ? "symmetry_y" : "front", 1, symmetry ? 0.0 : -d, {0, -1, 0}},
                          {"back", 1, d, {0, 1, 0}}};
  CHECK(mesh.boundaries.size() == 6);
  for (const Plane& plane : planes) {
    CAPTURE(plane.name);
    REQUIRE(mesh.boundaries.count(plane.name));
    for (int node : boundary_nodes(mesh, plane.name)) CHECK(std::abs(mesh.nodes[node][plane.axis] - plane.at) < 1e-12);
    for (const BoundaryFace& face : mesh.boundaries.at(plane.name))
      CHECK(face_normal(mesh, face).isApprox(plane.normal, 1e-12));
  }
  // contact_size over the disc, rim included; the far size at the top.
  const double r = request.fine_radius;
  const Eigen::Vector2d c = request.fine_centre;
  const double on_disc = mean_edge(mesh, [&](const Eigen::Vector3d& x) {
    return x.z() < request.contact_size && std::hypot(x.x() - c.x(), x.y() - c.y()) < r;
  });
  const double at_rim = mean_edge(mesh, [&](const Eigen::Vector3d& x) {
    return x.z() < request.contact_size && std::abs(std::hypot(x.x() - c.x(), x.y() - c.y()) - r) < 0.1 * r;
  });
  const double beside = mean_edge(mesh, [&](const Eigen::Vector3d& x) {  // 1 away from the disc: 0.1 + 0.3 · 1
    return x.z() < 0.3 && std::abs(std::hypot(x.x() - c.x(), x.y() - c.y()) - (r + 1)) < 0.3;
  });
  CHECK(beside > 2.5 * request.contact_size);
  const double far = mean_edge(mesh, [&](const Eigen::Vector3d& x) { return x.z() > 0.8 * request.height; });
  for (double edge : {on_disc, at_rim}) {
    CHECK(edge > 0.7 * request.contact_size);
    CHECK(edge < 1.6 * request.contact_size);
  }
  CHECK(far > 0.5 * request.size);
  CHECK(far < 1.6 * request.size);
}

TEST_CASE("the box with a punch's rim embedded has nodes on the circle and the same body", "[unit][gmsh][3d]") {
  const bool symmetry = GENERATE(false, true);
  CAPTURE(symmetry);
  BoxMeshRequest request;
  request.width = 8;
  request.depth = 6;
  request.height = 4;
  request.symmetry = symmetry;
  request.size = 1.0;
  request.contact_size = 0.1;
  request.grading = 0.3;
  request.fine_radius = 0.6;
  request.rim_radius = 0.5;
  request.fine_centre = symmetry ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(0.5, -0.75);
  const Mesh mesh = mesh_box(request);
  check_no_defect(mesh);
  CHECK(total_volume(mesh) == Approx((symmetry ? 0.25 : 1.0) * 8 * 6 * 4).epsilon(1e-12));
  CHECK(mesh.boundaries.size() == 6);
  check_boundaries_tile_surface(mesh);
  for (const BoundaryFace& face : mesh.boundaries.at("bottom"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  // Nodes on the rim, about one per contact_size of its length.
  const Eigen::Vector2d c = request.fine_centre;
  int on_rim = 0;
  for (int node : boundary_nodes(mesh, "bottom"))
    on_rim +=
        std::abs(std::hypot(mesh.nodes[node].x() - c.x(), mesh.nodes[node].y() - c.y()) - request.rim_radius) < 1e-9;
  const double length = (symmetry ? 0.25 : 1.0) * 2 * kPi * request.rim_radius;
  CHECK(on_rim > 0.7 * length / request.contact_size);
  CHECK(on_rim < 2.0 * length / request.contact_size);
}

TEST_CASE("the 3D estimates are within a factor of 2 of Gmsh's counts", "[unit][gmsh][3d][heavy]") {
  struct Sizes {
    double size, contact_size, grading, fine_radius;
  };
  for (const Sizes& s : {Sizes{0.2, 0.02, 0.1, 0.2}, Sizes{0.2, 0.015, 0.3, 0.2}, Sizes{0.3, 0.03, 0.2, 0.0}}) {
    for (bool symmetry : {true, false}) {
      CAPTURE(s.contact_size, s.grading, s.fine_radius, symmetry);
      HemisphereMeshRequest hemisphere;
      hemisphere.radius = 3;
      hemisphere.symmetry = symmetry;
      hemisphere.size = 3 * s.size;
      hemisphere.contact_size = 3 * s.contact_size;
      hemisphere.grading = s.grading;
      hemisphere.fine_radius = 3 * s.fine_radius;
      const double ratio = mesh_hemisphere(hemisphere).n_elements() / estimate_hemisphere_elements(hemisphere);
      CHECK(ratio > 0.5);
      CHECK(ratio < 2.0);
      BoxMeshRequest box;
      box.width = 12;
      box.depth = 8;
      box.height = 5;
      box.symmetry = symmetry;
      box.size = 10 * s.size;
      box.contact_size = 10 * s.contact_size;
      box.grading = s.grading;
      box.fine_radius = 10 * s.fine_radius;
      box.fine_centre = symmetry ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(1, -0.5);
      const double box_ratio = mesh_box(box).n_elements() / estimate_box_elements(box);
      CHECK(box_ratio > 0.5);
      CHECK(box_ratio < 2.0);
    }
  }
  // Without grading the contact size fills the body: more elements than with it.
  HemisphereMeshRequest uniform, graded;
  uniform.grading = 0;
  CHECK(estimate_hemisphere_elements(uniform) > 2 * estimate_hemisphere_elements(graded));
  BoxMeshRequest uniform_box, graded_box;
  uniform_box.grading = 0;
  CHECK(estimate_box_elements(uniform_box) > 2 * estimate_box_elements(graded_box));
  // An absurd request is estimated, not meshed, and the estimate is finite and huge.
  HemisphereMeshRequest absurd;
  absurd.contact_size = 1e-9;
  const double n = estimate_hemisphere_elements(absurd);
  CHECK(std::isfinite(n));
  CHECK(n > 1e20);
}

TEST_CASE("a .geo defining a volume is meshed in 3D with its physical groups", "[unit][gmsh][3d]") {
  ScratchDirectory directory;
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  // A 2 × 1 × 1 block by the built-in kernel, its bottom and top named, a corner named.
  const std::string geo = directory.write("block.geo", R"(
h = 0.25;
Point(1) = {0, 0, 0, h}; Point(2) = {2, 0, 0, h}; Point(3) = {2, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; };
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface(9) = {out[2], out[3], out[4], out[5]};
Physical Volume("block") = {out[1]};
Physical Point("corner") = {1};
)");
  const Mesh mesh = read_gmsh_file({geo, order});
  REQUIRE(mesh.dim == 3);
  CHECK(mesh.order == order);
  check_no_defect(mesh);
  CHECK(total_volume(mesh) == Approx(2.0).epsilon(1e-12));
  CHECK(mesh.regions.at("block").size() == static_cast<size_t>(mesh.n_elements()));
  REQUIRE(mesh.boundaries.count("bottom"));
  REQUIRE(mesh.boundaries.count("top"));
  REQUIRE(mesh.boundaries.count("9"));  // an unnamed group goes by its tag
  check_boundaries_tile_surface(mesh);
  for (const BoundaryFace& face : mesh.boundaries.at("bottom"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  for (const BoundaryFace& face : mesh.boundaries.at("top"))
    CHECK(face_normal(mesh, face).isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
  REQUIRE(mesh.points.at("corner").size() == 1);
  CHECK(mesh.nodes[mesh.points.at("corner").front()].norm() < 1e-15);
  // A .geo without volumes is still a 2D body.
  const std::string flat = directory.write("flat.geo", R"(
Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {0, 1, 0, 0.3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
)");
  const Mesh triangle = read_gmsh_file({flat, order});
  // The block's surfaces alone (a .msh saved with physical surfaces but no physical volume):
  // not read as a flat body, and the message says what is missing.
  const std::string shell = directory.write(
      "shell.msh", msh22({"1 0 0 0", "2 1 0 0", "3 0 1 0", "4 0 0 1"}, {"1 2 2 1 1 1 2 3", "2 2 2 1 2 1 2 4"}));
  CHECK_THROWS_WITH(read_gmsh_file({shell}), Catch::Matchers::Contains("add a Physical Volume"));
  CHECK(triangle.dim == 2);
  CHECK(triangle.type() == (order == 1 ? ElementType::Tri3 : ElementType::Tri6));
}

TEST_CASE("tetrahedral .msh defects and mixed orders are errors naming the file and the element or type",
          "[unit][gmsh][3d]") {
  ScratchDirectory directory;
  const std::vector<std::string> cube = {"1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0",
                                         "5 0 0 1", "6 1 0 1", "7 1 1 1", "8 0 1 1"};
  struct Case {
    std::string name, text, says;
  };
  const Case cases[] = {
      // Two positive tetrahedra and one inverted: the volume keeps its orientation, element 3 is an error.
      {"inverted.msh", msh22(cube, {"1 4 2 1 1 1 2 4 5", "2 4 2 1 1 2 3 4 7", "3 4 2 1 1 2 4 7 6"}),
       "element 3 is inverted"},
      {"flat.msh", msh22(cube, {"1 4 2 1 1 1 2 4 5", "2 4 2 1 1 1 2 3 4"}), "element 2 is degenerate"},
      {"hexahedron.msh", msh22(cube, {"1 5 2 1 1 1 2 3 4 5 6 7 8"}), "volume 1 holds 8-node hexahedron elements"},
      {"mixed.msh", msh22(kTet10Nodes, {"1 4 2 1 1 1 2 3 4", "2 11 2 1 1 1 2 3 4 5 6 7 8 9 10"}),
       "it mixes 4-node and 10-node tetrahedra"},
      {"wrong-face.msh", msh22(cube, {"1 4 2 1 1 1 2 4 5", "2 9 2 2 2 1 2 4 3 3 3"}),
       "physical surface \"2\" holds 6-node triangle elements"},
      // The same in 2D: one surface with 3- and 6-node triangles.
      {"mixed-2d.msh", msh22(kTet10Nodes, {"1 2 2 1 1 1 2 3", "2 9 2 1 1 1 2 3 5 6 7"}),
       "it mixes 3-node and 6-node triangles"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const std::string path = directory.write(c.name, c.text);
    CHECK_THROWS_AS(read_gmsh_file({path}), InputError);
    CHECK_THROWS_WITH(read_gmsh_file({path}), Catch::Matchers::Contains(c.name) && Catch::Matchers::Contains(c.says));
  }
}

TEST_CASE("a 2D body is still dim 2 with z = 0 and edge faces", "[unit][gmsh][3d]") {
  HalfDiscMeshRequest request;
  request.order = 2;
  request.fine = {{-0.2, 0.2}};
  const Mesh mesh = mesh_half_disc(request);
  CHECK(mesh.dim == 2);
  CHECK(mesh.type() == ElementType::Tri6);
  for (const auto& node : mesh.nodes) CHECK(node.z() == 0.0);
  for (const BoundaryFace& face : mesh.boundaries.at("arc")) {
    CHECK(face.n_nodes == 3);
    CHECK(std::abs((mesh.nodes[face.nodes[2]] - Eigen::Vector3d(0, 1, 0)).norm() - 1) < 1e-12);
  }
}

TEST_CASE("a scaled 3D request gives exactly the scaled mesh", "[unit][gmsh][3d]") {
  // The unit sizes of R = 0.7 (0.2 · 0.7 / 0.7 = 0.19999999999999998) once gave Gmsh's
  // Delaunay a different mesh; lengths are rounded in units of R (graded_size.hpp).
  const auto same = [](const Mesh& a, const Mesh& b, double scale) {
    REQUIRE(a.n_nodes() == b.n_nodes());
    REQUIRE(a.elements == b.elements);
    double worst = 0;
    for (int k = 0; k < a.n_nodes(); ++k) worst = std::max(worst, (scale * a.nodes[k] - b.nodes[k]).norm() / scale);
    CHECK(worst < 1e-13);
    for (const auto& [name, faces] : a.boundaries) CHECK(b.boundaries.at(name).size() == faces.size());
  };
  const auto hemisphere = [](double R) {
    HemisphereMeshRequest r;
    r.radius = R;
    r.symmetry = true;
    r.size = 0.2 * R;
    r.contact_size = 0.02 * R;
    r.grading = 0.2;
    r.fine_radius = 0.15 * R;
    return mesh_hemisphere(r);
  };
  const auto box = [](double L) {
    BoxMeshRequest b;
    b.width = 20 * L;
    b.depth = 16 * L;
    b.height = 10 * L;
    b.symmetry = true;
    b.size = 2 * L;
    b.contact_size = 0.1 * L;
    b.grading = 0.3;
    b.fine_radius = 1.1 * L;
    return mesh_box(b);
  };
  const Mesh unit_hemisphere = hemisphere(1), unit_box = box(1);
  for (double scale : {0.7, 3.0, 1e3, 1e-3}) {
    CAPTURE(scale);
    same(unit_hemisphere, hemisphere(scale), scale);
    same(unit_box, box(scale), scale);
  }
}

TEST_CASE("HXT meshes the same bodies with usable tetrahedra", "[unit][gmsh][3d]") {
  HemisphereMeshRequest hemisphere;
  hemisphere.symmetry = true;
  hemisphere.size = 0.3;
  hemisphere.contact_size = 0.05;
  hemisphere.order = 2;
  hemisphere.volume_algorithm = VolumeAlgorithm::Hxt;
  const Mesh mesh = mesh_hemisphere(hemisphere);
  check_no_defect(mesh);
  check_boundaries_tile_surface(mesh);
  CHECK(std::abs(isoparametric_volume(mesh) - kPi / 6) < 1e-3 * kPi / 6);
  BoxMeshRequest box;
  box.symmetry = true;
  box.volume_algorithm = VolumeAlgorithm::Hxt;
  const Mesh block = mesh_box(box);
  check_no_defect(block);
  CHECK(total_volume(block) == Approx(0.25).epsilon(1e-12));
}
