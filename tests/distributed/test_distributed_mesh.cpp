// The distributed mesh (src/distributed/distributed_mesh.hpp), run by every rank of mpirun
// -n 1, 2, 4 together: the ranks' parts put together are the serial mesh of the same scene,
// node for node (coordinates to the bit) and element for element (node order included), its
// boundary faces too; each node has one owner and one global number, which every copy agrees on.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <map>

#include "contactqp/mesh_file.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/scene.hpp"
#include "distributed/distributed_mesh.hpp"
#include "model/model_parts.hpp"
#include "test_support.hpp"

using namespace contactqp;
using contactqp::testing::source_path;

namespace {

using Point = std::array<double, 3>;

Point point(const Eigen::Vector3d& x) { return {x.x(), x.y(), x.z()}; }

// Every rank's values, on every rank (MPI_Allgatherv).
template <class T>
std::vector<T> all_of(const std::vector<T>& mine, MPI_Datatype type) {
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<T> all(offsets.back() + counts.back());
  MPI_Allgatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, MPI_COMM_WORLD);
  return all;
}

Scene scene_with(const std::string& path, int refinements, double contact_size) {
  Scene scene = load_scene(source_path(path));
  scene.body.mesh.refinements = refinements;
  scene.body.mesh.contact_size = contact_size;
  scene.body.mesh.size = std::max(scene.body.mesh.size, 8 * contact_size);
  return scene;
}

// The parts against the serial mesh: the same points, elements and boundary faces.
void check_against_serial(const Scene& scene) {
  start_process_runtime();
  Model reference;
  detail::choose_max_gap(scene, reference);
  const Mesh serial = scene_mesh(scene);
  const detail::MeshPart part = detail::distribute_body_mesh(scene, reference.max_gap, BuildOptions());
  const Mesh& mesh = part.mesh;
  INFO("rank " << process_rank() << " of " << process_count() << ": " << mesh.n_nodes() << " nodes, " << part.n_owned
               << " own, " << mesh.n_elements() << " elements");

  // Global numbers: own nodes consecutive, every copy of a node with its owner's coordinates.
  std::vector<double> own_coordinates;
  for (int k = 0; k < part.n_owned; ++k) {
    CHECK(part.global_node[k] == part.first_global_node + k);
    for (int c = 0; c < 3; ++c) own_coordinates.push_back(mesh.nodes[k][c]);
  }
  const std::vector<double> all_coordinates = all_of(own_coordinates, MPI_DOUBLE);
  REQUIRE(static_cast<long long>(all_coordinates.size()) == 3 * part.n_global_nodes);
  REQUIRE(part.n_global_nodes == serial.n_nodes());
  REQUIRE(part.n_global_elements == serial.n_elements());
  int disagreeing = 0;
  for (int k = 0; k < mesh.n_nodes(); ++k)
    for (int c = 0; c < 3; ++c) disagreeing += all_coordinates[3 * part.global_node[k] + c] != mesh.nodes[k][c];
  CHECK(disagreeing == 0);

  // Serial node of each global node, by its coordinates (exact).
  std::map<Point, int> serial_node;
  for (int k = 0; k < serial.n_nodes(); ++k) serial_node.emplace(point(serial.nodes[k]), k);
  REQUIRE(static_cast<int>(serial_node.size()) == serial.n_nodes());
  std::vector<int> to_serial(part.n_global_nodes, -1);
  for (long long g = 0; g < part.n_global_nodes; ++g) {
    const auto it = serial_node.find({all_coordinates[3 * g], all_coordinates[3 * g + 1], all_coordinates[3 * g + 2]});
    if (it != serial_node.end()) to_serial[g] = it->second;
  }
  CHECK(std::count(to_serial.begin(), to_serial.end(), -1) == 0);

  // Elements, in serial node numbers with their node order, as sorted lists.
  const int npe = mesh.nodes_per_element();
  std::vector<int> mine;
  for (int node : mesh.elements) mine.push_back(to_serial[part.global_node[node]]);
  std::vector<int> all = all_of(mine, MPI_INT);
  std::vector<std::vector<int>> ours, theirs;
  for (std::size_t e = 0; e < all.size(); e += npe) ours.emplace_back(all.begin() + e, all.begin() + e + npe);
  for (int e = 0; e < serial.n_elements(); ++e) theirs.emplace_back(serial.element(e), serial.element(e) + npe);
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  CHECK(ours == theirs);

  // Boundary faces, each on one rank only.
  for (const auto& [name, faces] : serial.boundaries) {
    INFO("boundary " << name);
    REQUIRE(mesh.boundaries.count(name) == 1);
    std::vector<int> flat;
    for (const BoundaryFace& face : mesh.boundaries.at(name)) {
      flat.push_back(face.n_nodes);
      for (int k = 0; k < face.n_nodes; ++k) flat.push_back(to_serial[part.global_node[face.nodes[k]]]);
    }
    const std::vector<int> gathered = all_of(flat, MPI_INT);
    std::vector<std::vector<int>> got, expected;
    for (std::size_t k = 0; k < gathered.size(); k += 1 + gathered[k])
      got.emplace_back(gathered.begin() + k + 1, gathered.begin() + k + 1 + gathered[k]);
    for (const BoundaryFace& face : faces) expected.emplace_back(face.nodes.begin(), face.nodes.begin() + face.n_nodes);
    std::sort(got.begin(), got.end());
    std::sort(expected.begin(), expected.end());
    CHECK(got == expected);
  }
  // The whole body's outer boundary, on the ranks of its faces' elements.
  long long outer = static_cast<long long>(part.outer.size()), total = 0;
  MPI_Allreduce(&outer, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  CHECK(total == static_cast<long long>(outer_boundary(serial).size()));
}

}  // namespace

TEST_CASE("the ranks' parts of a refined hemisphere are its serial refinement", "[distributed]") {
  check_against_serial(scene_with("scenes/hertz-sphere.json", 1, 0.05));
}

TEST_CASE("the ranks' parts of a hemisphere refined twice, 4-node", "[distributed]") {
  Scene scene = scene_with("scenes/hertz-sphere.json", 2, 0.08);
  scene.body.mesh.order = 1;
  check_against_serial(scene);
}

TEST_CASE("the ranks' parts of a refined half disc (6-node triangles) are its serial refinement", "[distributed]") {
  check_against_serial(scene_with("scenes/hertz.json", 2, 0.01));
}

TEST_CASE("a hemisphere meshed by Gmsh directly is split between the ranks as it is", "[distributed]") {
  check_against_serial(scene_with("scenes/hertz-sphere.json", 0, 0.05));
}

TEST_CASE("the shipped sphere scene is split between the ranks as it is", "[distributed]") {
  check_against_serial(load_scene(source_path("scenes/hertz-sphere.json")));
}
