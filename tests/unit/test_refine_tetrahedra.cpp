// Uniform refinement of tetrahedra (src/mesh/refine_tetrahedra.cpp): a cube of six tetrahedra
// and random ones against exact volumes and areas, and the refined hemisphere against its
// exact geometry (nodes on the sphere, the top and the symmetry planes, its volume).
#include <Eigen/Dense>  // determinant()
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <iterator>
#include <random>
#include <set>

#include "contactqp/mesh.hpp"
#include "mesh/hemisphere_mesher.hpp"
#include "mesh/refine.hpp"
#include "mesh/shape_functions.hpp"
#include "mesh_volume.hpp"
#include "qp/pi.hpp"

using namespace contactqp;
using namespace contactqp::detail;
using contactqp::testing::check_boundaries_tile_surface;
using contactqp::testing::isoparametric_volume;
using contactqp::testing::total_volume;

namespace {

Eigen::Vector3d identity_snap(const std::string&, const Eigen::Vector3d& x) { return x; }

double face_area(const Mesh& mesh, const BoundaryFace& face) {
  const Eigen::Vector3d& a = mesh.nodes[face.nodes[0]];
  return 0.5 * (mesh.nodes[face.nodes[1]] - a).cross(mesh.nodes[face.nodes[2]] - a).norm();
}

double boundary_area(const Mesh& mesh) {
  double area = 0;
  for (const auto& [name, faces] : mesh.boundaries)
    for (const BoundaryFace& face : faces) area += face_area(mesh, face);
  return area;
}

// Interior mid-edge nodes of a 10-node mesh sit at their edge's midpoint, in our order
// (01, 12, 20, 03, 13, 23); those of `curved` may not.
void check_mid_edges(const Mesh& mesh, const std::vector<int>& curved) {
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  double worst = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int k = 0; k < 6; ++k) {
      if (std::binary_search(curved.begin(), curved.end(), v[4 + k])) continue;
      const Eigen::Vector3d middle = 0.5 * (mesh.nodes[v[edges[k][0]]] + mesh.nodes[v[edges[k][1]]]);
      worst = std::max(worst, (mesh.nodes[v[4 + k]] - middle).norm());
    }
  }
  CHECK(worst <= 1e-15);
}

int count_edges(const Mesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.insert(std::minmax(v[i], v[j]));
  }
  return static_cast<int>(edges.size());
}

int distinct_positions(const Mesh& mesh) {
  std::set<std::array<double, 3>> positions;
  for (const Eigen::Vector3d& x : mesh.nodes) positions.insert({x.x(), x.y(), x.z()});
  return static_cast<int>(positions.size());
}

// The unit cube cut into six tetrahedra around its diagonal 0–7 (Kuhn's), all positive, its
// 12 outer triangles the boundary "outer", the first three tetrahedra a region, a named corner.
Mesh unit_cube() {
  Mesh mesh;
  mesh.dim = 3;
  mesh.order = 1;
  for (int k = 0; k < 8; ++k) mesh.nodes.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  const int paths[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};  // the axes' order from 0 to 7
  for (const auto& p : paths) {
    int tet[4] = {0, p[0], p[0] + p[1], 7};
    mesh.elements.insert(mesh.elements.end(), tet, tet + 4);
    if (element_measure(mesh, mesh.n_elements() - 1) < 0) std::swap(mesh.elements.end()[-1], mesh.elements.end()[-2]);
  }
  mesh.boundaries["outer"] = outer_boundary(mesh);
  mesh.regions["half"] = {0, 1, 2};
  mesh.points["corner"] = {7};
  return mesh;
}

}  // namespace

TEST_CASE("a cube of six tetrahedra refined: 8 children each, the exact volume and area, all positive",
          "[unit][refine][3d]") {
  const Mesh cube = unit_cube();
  REQUIRE(cube.n_elements() == 6);
  REQUIRE(cube.boundaries.at("outer").size() == 12);
  for (int times : {1, 2}) {
    CAPTURE(times);
    const Mesh fine = refine_tetrahedra(cube, times, 1, identity_snap);
    const int children = times == 1 ? 8 : 64;
    CHECK(fine.n_elements() == 6 * children);
    CHECK(fine.boundaries.at("outer").size() == (times == 1 ? 48u : 192u));  // each triangle into 4, per split
    CHECK(std::abs(total_volume(fine) - 1) <= 1e-14);
    for (int e = 0; e < fine.n_elements(); ++e) REQUIRE(element_measure(fine, e) == Approx(1.0 / 6 / children));
    CHECK(std::abs(boundary_area(fine) - 6) <= 1e-13);
    check_boundaries_tile_surface(fine);
    // Outward faces (orient() re-oriented them): each normal points away from the centre.
    for (const BoundaryFace& face : fine.boundaries.at("outer")) {
      const Eigen::Vector3d middle =
          (fine.nodes[face.nodes[0]] + fine.nodes[face.nodes[1]] + fine.nodes[face.nodes[2]]) / 3;
      CHECK(face_normal(fine, face).dot(middle - Eigen::Vector3d(0.5, 0.5, 0.5)) > 0);
    }
    // The nodes: the cube's, then one per edge of the mesh split, no two at one place.
    const Mesh parent = times == 1 ? cube : refine_tetrahedra(cube, 1, 1, identity_snap);
    CHECK(fine.n_nodes() == parent.n_nodes() + count_edges(parent));
    if (times == 1) CHECK(fine.n_nodes() == 27);  // the grid of spacing 1/2
    CHECK(distinct_positions(fine) == fine.n_nodes());
    for (int k = 0; k < 8; ++k) CHECK(fine.nodes[k] == cube.nodes[k]);
    CHECK(fine.points.at("corner") == std::vector<int>{7});
    // The region holds exactly the children of its elements (8e … 8e + 7 of each).
    CHECK(fine.regions.at("half").size() == 3u * children);
    const std::vector<int>& half = fine.regions.at("half");
    for (std::size_t k = 0; k < half.size(); ++k) CHECK(half[k] == static_cast<int>(k));
  }
  // Order 2: 10-node tetrahedra with mid-edge nodes at the midpoints, 6-node faces.
  const Mesh quadratic = refine_tetrahedra(cube, 1, 2, identity_snap);
  CHECK(quadratic.type() == ElementType::Tet10);
  CHECK(quadratic.n_elements() == 48);
  const Mesh linear = refine_tetrahedra(cube, 1, 1, identity_snap);
  CHECK(quadratic.n_nodes() == linear.n_nodes() + count_edges(linear));
  CHECK(distinct_positions(quadratic) == quadratic.n_nodes());
  check_mid_edges(quadratic, {});
  for (const BoundaryFace& face : quadratic.boundaries.at("outer")) {
    REQUIRE(face.n_nodes == 6);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d middle = 0.5 * (quadratic.nodes[face.nodes[k]] + quadratic.nodes[face.nodes[(k + 1) % 3]]);
      CHECK((quadratic.nodes[face.nodes[3 + k]] - middle).norm() <= 1e-15);
    }
  }
  CHECK(std::abs(isoparametric_volume(quadratic) - 1) <= 1e-13);
  CHECK_THROWS_WITH(refine_tetrahedra(quadratic, 1, 1, identity_snap),
                    "refine_tetrahedra: needs a mesh of 4-node tetrahedra");
}

TEST_CASE("random tetrahedra: children of an eighth of the volume, the octahedron cut along its shortest diagonal",
          "[unit][refine][3d]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::set<std::set<int>> diagonals_used;
  for (int trial = 0; trial < 200; ++trial) {
    Mesh tet;
    tet.dim = 3;
    tet.order = 1;
    for (int k = 0; k < 4; ++k) tet.nodes.emplace_back(coordinate(random), coordinate(random), coordinate(random));
    tet.elements = {0, 1, 2, 3};
    const double volume = element_measure(tet, 0);
    if (std::abs(volume) < 1e-3) continue;
    if (volume < 0) std::swap(tet.elements[2], tet.elements[3]);
    const Mesh fine = refine_tetrahedra(tet, 1, 1, identity_snap);
    REQUIRE(fine.n_elements() == 8);
    for (int e = 0; e < 8; ++e) CHECK(element_measure(fine, e) == Approx(std::abs(volume) / 8).epsilon(1e-12));
    // Children 4–7 are the octahedron's: the two nodes they all hold are its diagonal.
    std::set<int> common(fine.element(4), fine.element(4) + 4);
    for (int e = 5; e < 8; ++e) {
      std::set<int> kept;
      for (int node : common)
        if (std::count(fine.element(e), fine.element(e) + 4, node)) kept.insert(node);
      common = kept;
    }
    REQUIRE(common.size() == 2);
    const double chosen = (fine.nodes[*common.begin()] - fine.nodes[*common.rbegin()]).norm();
    // The three diagonals join the mid-edge nodes of opposite edges: nodes 4–9 are the new ones.
    const int opposite[3][2][2] = {{{0, 1}, {2, 3}}, {{0, 2}, {1, 3}}, {{0, 3}, {1, 2}}};
    const int* v = tet.elements.data();
    for (const auto& pair : opposite) {
      const Eigen::Vector3d a = 0.5 * (tet.nodes[v[pair[0][0]]] + tet.nodes[v[pair[0][1]]]);
      const Eigen::Vector3d b = 0.5 * (tet.nodes[v[pair[1][0]]] + tet.nodes[v[pair[1][1]]]);
      CHECK(chosen <= (a - b).norm() * (1 + 1e-12));
    }
    diagonals_used.insert(common);
  }
  CHECK(diagonals_used.size() == 3);  // each of the three was the shortest somewhere
}

TEST_CASE("the refined hemisphere: new nodes on the sphere, the top and the planes, and a closer volume",
          "[unit][refine][gmsh][3d]") {
  const int order = GENERATE(1, 2);
  const int refinements = GENERATE(1, 2);
  CAPTURE(order, refinements);
  HemisphereMeshRequest request;
  request.radius = 2.5;  // refined in units of R and scaled
  request.symmetry = true;
  request.size = 0.5;
  request.contact_size = 0.05;
  request.grading = 0.3;
  request.fine_radius = 0.5;
  request.order = order;
  request.refinements = refinements;
  const Mesh mesh = mesh_hemisphere(request);
  const double R = request.radius;
  REQUIRE(mesh.dim == 3);
  REQUIRE(mesh.order == order);
  check_boundaries_tile_surface(mesh);

  const Eigen::Vector3d centre(0, 0, R);
  const std::vector<int> surface = boundary_nodes(mesh, "surface"), top = boundary_nodes(mesh, "top");
  for (int node : surface) CHECK(std::abs((mesh.nodes[node] - centre).norm() - R) <= 1e-12 * R);
  for (int node : top) CHECK(std::abs(mesh.nodes[node].z() - R) <= 1e-12 * R);
  for (int node : boundary_nodes(mesh, "symmetry_x")) CHECK(std::abs(mesh.nodes[node].x()) <= 1e-12 * R);
  for (int node : boundary_nodes(mesh, "symmetry_y")) CHECK(std::abs(mesh.nodes[node].y()) <= 1e-12 * R);
  // The rim (sphere and top) holds new nodes too: they stayed on both.
  std::vector<int> rim;
  std::set_intersection(surface.begin(), surface.end(), top.begin(), top.end(), std::back_inserter(rim));
  CHECK(rim.size() > 8);
  for (const BoundaryFace& face : mesh.boundaries.at("surface")) CHECK(face.n_nodes == (order == 1 ? 3 : 6));
  if (order == 2) check_mid_edges(mesh, surface);

  // Gmsh's coarse mesh it was refined from (sizes and grading 2ⁿ times larger, 4-node): eight
  // children per tetrahedron and split, and a volume closer to the quarter half ball's (both
  // inscribed, their vertices on the sphere); curved 10-node elements closer still. (How the
  // count compares with Gmsh's direct mesh of the fine sizes: tests/unit/test_mesh_file.cpp.)
  HemisphereMeshRequest coarse = request;
  coarse.size *= std::ldexp(1.0, refinements);
  coarse.contact_size *= std::ldexp(1.0, refinements);
  coarse.grading *= std::ldexp(1.0, refinements);
  coarse.refinements = 0;
  coarse.order = 1;
  const Mesh coarse_mesh = mesh_hemisphere(coarse);
  CHECK(mesh.n_elements() == coarse_mesh.n_elements() << (3 * refinements));
  const double exact = 2 * kPi * R * R * R / 3 / 4;
  const double straight = total_volume(mesh), coarse_volume = total_volume(coarse_mesh);
  CAPTURE(straight / exact, coarse_volume / exact);
  CHECK(straight < exact);
  CHECK(straight > exact * (1 - 0.02));
  CHECK(exact - straight < 0.5 * (exact - coarse_volume));
  if (order == 2) CHECK(std::abs(isoparametric_volume(mesh) - exact) < 1e-3 * exact);
}
