// distribute_body_mesh() (distributed_mesh.hpp).
#include "distributed_mesh.hpp"

#include <petscsf.h>

#include <algorithm>
#include <array>
#include <climits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "coarse_lattice.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/phases.hpp"
#include "element_partition.hpp"
#include "model/model_parts.hpp"
#include "petsc/petsc_runtime.hpp"
#include "world.hpp"

namespace contactqp::detail {
namespace {

// The hidden boundary that carries the whole body's outer faces through the refinement (no
// scene can name it: names come from JSON strings and Gmsh's physical names, never with '<').
const char* const kOuter = "<outer>";

// What rank 0 sends each rank: integers and coordinates, read back in the order written.
struct Packet {
  std::vector<int> ints;
  std::vector<double> reals;
  void put(int value) { ints.push_back(value); }
  void put(const std::vector<int>& values) {
    put(static_cast<int>(values.size()));
    ints.insert(ints.end(), values.begin(), values.end());
  }
};

class Reader {
 public:
  explicit Reader(const Packet& packet) : packet_(packet) {}
  int get() { return packet_.ints.at(next_++); }
  std::vector<int> get_vector() {
    const int n = get();
    std::vector<int> out(packet_.ints.begin() + next_, packet_.ints.begin() + next_ + n);
    next_ += n;
    return out;
  }

 private:
  const Packet& packet_;
  std::size_t next_ = 0;
};

// The names of a map's entries, for the ranks that did not mesh.
template <class Map>
std::vector<std::string> names_of(const Map& map) {
  std::vector<std::string> names;
  for (const auto& entry : map) names.push_back(entry.first);
  return names;
}

void broadcast_names(std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += name + '\n';
  int length = static_cast<int>(joined.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  joined.resize(length);
  MPI_Bcast(joined.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  names.clear();
  for (std::size_t start = 0; start < joined.size();) {
    const std::size_t end = joined.find('\n', start);
    names.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
}

// What every rank needs to know of the coarse mesh besides its part.
struct CoarseFacts {
  int dim = 3, order = 1;
  long long n_elements = 0;
  CoarseEntities totals;  // counts only
  std::vector<std::string> boundaries, regions, points;
};

void broadcast_facts(CoarseFacts& facts) {
  long long numbers[7] = {facts.dim,
                          facts.order,
                          facts.n_elements,
                          facts.totals.n_vertices,
                          facts.totals.n_edges,
                          facts.totals.n_faces,
                          facts.totals.n_cells};
  MPI_Bcast(numbers, 7, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  facts.dim = static_cast<int>(numbers[0]);
  facts.order = static_cast<int>(numbers[1]);
  facts.n_elements = numbers[2];
  facts.totals.dim = facts.dim;
  facts.totals.n_vertices = numbers[3];
  facts.totals.n_edges = numbers[4];
  facts.totals.n_faces = numbers[5];
  facts.totals.n_cells = numbers[6];
  broadcast_names(facts.boundaries);
  broadcast_names(facts.regions);
  broadcast_names(facts.points);
}

// Rank 0: each rank's part of the coarse mesh — its elements, then the ghosts (elements that
// share a vertex with one of its own) — with their nodes, boundary faces, regions and points.
std::vector<Packet> pack_parts(const Mesh& coarse, const CoarseEntities& entities, const std::vector<int>& part,
                               int ranks, bool refined) {
  const int n_elements = coarse.n_elements(), npe = coarse.nodes_per_element(), nv = coarse.dim + 1;
  const int n_edges = edges_per_simplex(coarse.dim);
  // The ranks whose elements touch each vertex.
  std::vector<std::vector<int>> ranks_at(coarse.n_nodes());
  for (int e = 0; e < n_elements; ++e)
    for (int k = 0; k < nv; ++k) {
      std::vector<int>& at = ranks_at[coarse.element(e)[k]];
      if (std::find(at.begin(), at.end(), part[e]) == at.end()) at.push_back(part[e]);
    }
  std::vector<std::vector<int>> owned(ranks), ghosts(ranks);
  for (int e = 0; e < n_elements; ++e) {
    owned[part[e]].push_back(e);
    std::vector<int> touching;
    for (int k = 0; k < nv; ++k)
      for (int r : ranks_at[coarse.element(e)[k]])
        if (r != part[e] && std::find(touching.begin(), touching.end(), r) == touching.end()) touching.push_back(r);
    for (int r : touching) ghosts[r].push_back(e);
  }
  ranks_at = {};
  // Each boundary face's element, by its sorted vertices.
  std::map<std::array<int, 4>, int> element_of_face;
  for (int e = 0; e < n_elements; ++e)
    for (const auto& local : element_faces(coarse.type())) {
      std::array<int, 4> key = {-1, -1, -1, -1};
      for (int k = 0; k < coarse.dim; ++k) key[k] = coarse.element(e)[local[k]];
      element_of_face.emplace(simplex_key(key, coarse.dim), e);
    }
  const auto face_element = [&](const BoundaryFace& face) {
    std::array<int, 4> key = {-1, -1, -1, -1};
    for (int k = 0; k < coarse.dim; ++k) key[k] = face.nodes[k];
    const auto it = element_of_face.find(simplex_key(key, coarse.dim));
    return it == element_of_face.end() ? -1 : it->second;
  };
  std::map<std::string, std::vector<BoundaryFace>> boundaries = coarse.boundaries;
  boundaries[kOuter] = outer_boundary(coarse);
  std::map<std::string, std::vector<int>> faces_element;
  for (const auto& [name, faces] : boundaries)
    for (const BoundaryFace& face : faces) faces_element[name].push_back(face_element(face));

  std::vector<Packet> packets(ranks);
  std::vector<int> local_of_node(coarse.n_nodes(), -1), local_of_element(n_elements, -1);
  for (int r = 0; r < ranks; ++r) {
    Packet& packet = packets[r];
    std::vector<int> elements = owned[r];
    elements.insert(elements.end(), ghosts[r].begin(), ghosts[r].end());
    std::vector<int> nodes;
    for (std::size_t i = 0; i < elements.size(); ++i) {
      local_of_element[elements[i]] = static_cast<int>(i);
      for (int k = 0; k < npe; ++k) {
        const int node = coarse.element(elements[i])[k];
        if (local_of_node[node] < 0) {
          local_of_node[node] = static_cast<int>(nodes.size());
          nodes.push_back(node);
        }
      }
    }
    packet.put(nodes);
    for (int node : nodes)
      for (int c = 0; c < 3; ++c) packet.reals.push_back(coarse.nodes[node][c]);
    packet.put(static_cast<int>(owned[r].size()));
    packet.put(elements);  // their global numbers
    std::vector<int> connectivity, edges, faces;
    for (int e : elements) {
      for (int k = 0; k < npe; ++k) connectivity.push_back(local_of_node[coarse.element(e)[k]]);
      if (!refined) continue;
      for (int k = 0; k < n_edges; ++k)
        edges.push_back(entities.element_edges[static_cast<std::size_t>(e) * n_edges + k]);
      if (coarse.dim == 3)
        for (int k = 0; k < 4; ++k) faces.push_back(entities.element_faces[static_cast<std::size_t>(e) * 4 + k]);
    }
    packet.put(connectivity);
    packet.put(edges);
    packet.put(faces);
    // Boundary faces of the part's elements, this rank's own elements' first.
    for (const auto& [name, all_faces] : boundaries) {
      const std::vector<int>& of = faces_element[name];
      std::vector<int> mine, theirs;
      for (std::size_t f = 0; f < all_faces.size(); ++f) {
        const int e = of[f];
        if (e < 0 || local_of_element[e] < 0) continue;
        std::vector<int>& to = part[e] == r ? mine : theirs;
        to.push_back(all_faces[f].n_nodes);
        for (int k = 0; k < all_faces[f].n_nodes; ++k) to.push_back(local_of_node[all_faces[f].nodes[k]]);
      }
      packet.put(mine);
      packet.put(theirs);
    }
    for (const auto& [name, members] : coarse.regions) {
      std::vector<int> local;
      for (int e : members)
        if (local_of_element[e] >= 0) local.push_back(local_of_element[e]);
      std::sort(local.begin(), local.end());
      packet.put(local);
    }
    for (const auto& [name, members] : coarse.points) {
      std::vector<int> local;
      for (int node : members)
        if (local_of_node[node] >= 0) local.push_back(local_of_node[node]);
      packet.put(local);
    }
    for (int node : nodes) local_of_node[node] = -1;
    for (int e : elements) local_of_element[e] = -1;
  }
  return packets;
}

// Rank 0 sends each rank its packet (MPI_Scatterv); rank 0 keeps its own.
Packet scatter_packets(std::vector<Packet>& packets) {
  const int rank = world_rank(), ranks = world_size();
  std::vector<int> int_counts(ranks, 0), real_counts(ranks, 0), int_offsets(ranks, 0), real_offsets(ranks, 0);
  std::vector<int> ints;
  std::vector<double> reals;
  if (rank == 0) {
    for (int r = 0; r < ranks; ++r) {
      int_counts[r] = static_cast<int>(packets[r].ints.size());
      real_counts[r] = static_cast<int>(packets[r].reals.size());
      int_offsets[r] = static_cast<int>(ints.size());
      real_offsets[r] = static_cast<int>(reals.size());
      ints.insert(ints.end(), packets[r].ints.begin(), packets[r].ints.end());
      reals.insert(reals.end(), packets[r].reals.begin(), packets[r].reals.end());
      packets[r] = Packet();
    }
  }
  int counts[2] = {0, 0};
  std::vector<int> both(2 * ranks);
  for (int r = 0; r < ranks; ++r) both[2 * r] = int_counts[r], both[2 * r + 1] = real_counts[r];
  MPI_Scatter(both.data(), 2, MPI_INT, counts, 2, MPI_INT, 0, MPI_COMM_WORLD);
  Packet mine;
  mine.ints.resize(counts[0]);
  mine.reals.resize(counts[1]);
  MPI_Scatterv(ints.data(), int_counts.data(), int_offsets.data(), MPI_INT, mine.ints.data(), counts[0], MPI_INT, 0,
               MPI_COMM_WORLD);
  MPI_Scatterv(reals.data(), real_counts.data(), real_offsets.data(), MPI_DOUBLE, mine.reals.data(), counts[1],
               MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return mine;
}

// A rank's coarse part as a Mesh, with what naming its refined nodes needs.
struct CoarsePart {
  Mesh mesh;
  std::vector<int> vertex, cell, edges, faces;  // global numbers (coarse_lattice.hpp)
  int n_owned_elements = 0;
  std::map<std::string, int> n_owned_faces;
};

CoarsePart unpack_part(const Packet& packet, const CoarseFacts& facts) {
  CoarsePart part;
  Reader in(packet);
  Mesh& mesh = part.mesh;
  mesh.dim = facts.dim;
  mesh.order = facts.order;
  part.vertex = in.get_vector();
  mesh.nodes.resize(part.vertex.size());
  for (std::size_t k = 0; k < part.vertex.size(); ++k)
    mesh.nodes[k] = Eigen::Vector3d(packet.reals[3 * k], packet.reals[3 * k + 1], packet.reals[3 * k + 2]);
  part.n_owned_elements = in.get();
  part.cell = in.get_vector();
  mesh.elements = in.get_vector();
  part.edges = in.get_vector();
  part.faces = in.get_vector();
  std::vector<std::string> boundaries = facts.boundaries;
  boundaries.push_back(kOuter);
  std::sort(boundaries.begin(), boundaries.end());  // the order pack_parts wrote them (a std::map's)
  for (const std::string& name : boundaries) {
    std::vector<BoundaryFace>& faces = mesh.boundaries[name];
    for (int pass = 0; pass < 2; ++pass) {
      const std::vector<int> flat = in.get_vector();
      for (std::size_t k = 0; k < flat.size();) {
        BoundaryFace face;
        face.n_nodes = flat[k++];
        for (int j = 0; j < face.n_nodes; ++j) face.nodes[j] = flat[k++];
        faces.push_back(face);
      }
      if (pass == 0) part.n_owned_faces[name] = static_cast<int>(faces.size());
    }
  }
  for (const std::string& name : facts.regions) mesh.regions[name] = in.get_vector();
  for (const std::string& name : facts.points) mesh.points[name] = in.get_vector();
  return part;
}

// The children of the part's own elements and faces, with only the nodes they use (in their
// order); `names` follows the nodes.
Mesh keep_own_children(const Mesh& refined, const CoarsePart& part, long long element_factor, long long face_factor,
                       std::vector<long long>& names) {
  Mesh kept;
  kept.dim = refined.dim;
  kept.order = refined.order;
  const int npe = refined.nodes_per_element();
  const std::size_t n_kept = static_cast<std::size_t>(part.n_owned_elements) * element_factor;
  std::vector<int> new_index(refined.n_nodes(), -1);
  std::vector<int> old_of_new;
  kept.elements.assign(refined.elements.begin(), refined.elements.begin() + n_kept * npe);
  for (int& node : kept.elements) {
    if (new_index[node] < 0) {
      new_index[node] = static_cast<int>(old_of_new.size());
      old_of_new.push_back(node);
    }
    node = new_index[node];
  }
  kept.nodes.resize(old_of_new.size());
  std::vector<long long> kept_names(old_of_new.size());
  for (std::size_t k = 0; k < old_of_new.size(); ++k) {
    kept.nodes[k] = refined.nodes[old_of_new[k]];
    kept_names[k] = names[old_of_new[k]];
  }
  names = std::move(kept_names);
  for (const auto& [name, faces] : refined.boundaries) {
    std::vector<BoundaryFace>& out = kept.boundaries[name];
    const std::size_t n = static_cast<std::size_t>(part.n_owned_faces.at(name)) * face_factor;
    out.assign(faces.begin(), faces.begin() + n);
    for (BoundaryFace& face : out)
      for (int k = 0; k < face.n_nodes; ++k) face.nodes[k] = new_index[face.nodes[k]];
  }
  for (const auto& [name, elements] : refined.regions) {
    std::vector<int>& out = kept.regions[name];
    for (int e : elements)
      if (static_cast<std::size_t>(e) < n_kept) out.push_back(e);
  }
  for (const auto& [name, nodes] : refined.points) {
    std::vector<int>& out = kept.points[name];
    for (int node : nodes)
      if (new_index[node] >= 0) out.push_back(new_index[node]);
  }
  return kept;
}

// Renumbers the nodes: node k becomes order[k]'s position (order lists the old nodes).
void renumber_nodes(Mesh& mesh, std::vector<BoundaryFace>& outer, const std::vector<int>& order) {
  std::vector<int> new_index(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) new_index[order[k]] = static_cast<int>(k);
  std::vector<Eigen::Vector3d> nodes(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) nodes[k] = mesh.nodes[order[k]];
  mesh.nodes = std::move(nodes);
  for (int& node : mesh.elements) node = new_index[node];
  for (auto& [name, faces] : mesh.boundaries)
    for (BoundaryFace& face : faces)
      for (int k = 0; k < face.n_nodes; ++k) face.nodes[k] = new_index[face.nodes[k]];
  for (BoundaryFace& face : outer)
    for (int k = 0; k < face.n_nodes; ++k) face.nodes[k] = new_index[face.nodes[k]];
  for (auto& [name, nodes] : mesh.points)
    for (int& node : nodes) node = new_index[node];
}

// A PetscSF from this rank's nodes (leaves) to the names' layout [0, n_names) (roots spread
// evenly over the ranks): the meeting point of the copies of one node.
PetscSF names_sf(const std::vector<long long>& names, long long n_names) {
  if (n_names > INT_MAX)
    throw std::runtime_error("the refined mesh has more node names (" + std::to_string(n_names) +
                             ") than PETSc's 32-bit indices hold; use fewer body.mesh.refinements");
  PetscLayout layout = nullptr;
  check_petsc(PetscLayoutCreate(PETSC_COMM_WORLD, &layout), "PetscLayoutCreate");
  PetscLayoutSetSize(layout, static_cast<PetscInt>(n_names));
  PetscLayoutSetBlockSize(layout, 1);
  check_petsc(PetscLayoutSetUp(layout), "PetscLayoutSetUp");
  std::vector<PetscInt> remote(names.begin(), names.end());
  for (long long name : names)
    if (name < 0 || name >= n_names)
      throw std::logic_error("distributed mesh: a node name " + std::to_string(name) + " outside [0, " +
                             std::to_string(n_names) + ")");
  PetscSF sf = nullptr;
  check_petsc(PetscSFCreate(PETSC_COMM_WORLD, &sf), "PetscSFCreate");
  check_petsc(PetscSFSetGraphLayout(sf, layout, static_cast<PetscInt>(remote.size()), nullptr, PETSC_COPY_VALUES,
                                    remote.data()),
              "PetscSFSetGraphLayout");
  PetscLayoutDestroy(&layout);
  check_petsc(PetscSFSetUp(sf), "PetscSFSetUp");
  return sf;
}

// Each leaf's entry becomes the `op` (MPI_MIN, MPI_MAX) of the entries of all leaves with its name.
void combine_by_name(PetscSF sf, PetscInt n_roots, std::vector<int>& values, MPI_Op op, int neutral) {
  std::vector<int> roots(n_roots, neutral);
  check_petsc(PetscSFReduceBegin(sf, MPI_INT, values.data(), roots.data(), op), "PetscSFReduceBegin");
  check_petsc(PetscSFReduceEnd(sf, MPI_INT, values.data(), roots.data(), op), "PetscSFReduceEnd");
  check_petsc(PetscSFBcastBegin(sf, MPI_INT, roots.data(), values.data(), MPI_REPLACE), "PetscSFBcastBegin");
  check_petsc(PetscSFBcastEnd(sf, MPI_INT, roots.data(), values.data(), MPI_REPLACE), "PetscSFBcastEnd");
}

// Ownership (the lowest rank holding a node), own nodes first, global numbers, the node SF.
void number_nodes(MeshPart& out, const std::vector<long long>& names, long long n_names) {
  const int rank = world_rank();
  const int n = out.mesh.n_nodes();
  PetscSF by_name = names_sf(names, n_names);
  PetscInt n_roots = 0;
  PetscSFGetGraph(by_name, &n_roots, nullptr, nullptr, nullptr);
  std::vector<int> owner(n, rank);
  combine_by_name(by_name, n_roots, owner, MPI_MIN, INT_MAX);
  std::vector<int> order;
  order.reserve(n);
  for (int k = 0; k < n; ++k)
    if (owner[k] == rank) order.push_back(k);
  out.n_owned = static_cast<int>(order.size());
  for (int k = 0; k < n; ++k)
    if (owner[k] != rank) order.push_back(k);
  renumber_nodes(out.mesh, out.outer, order);
  int first = 0;
  MPI_Exscan(&out.n_owned, &first, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) first = 0;
  out.first_global_node = first;
  // The owner's number for every copy, met by name (the name SF's leaves are in the old order).
  std::vector<int> global(n, -1);
  for (int k = 0; k < out.n_owned; ++k) global[order[k]] = first + k;
  combine_by_name(by_name, n_roots, global, MPI_MAX, -1);
  PetscSFDestroy(&by_name);
  out.global_node.resize(n);
  for (int k = 0; k < n; ++k) out.global_node[k] = global[order[k]];
  long long owned = out.n_owned, total = 0;
  MPI_Allreduce(&owned, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  out.n_global_nodes = total;

  PetscLayout layout = nullptr;
  check_petsc(PetscLayoutCreate(PETSC_COMM_WORLD, &layout), "PetscLayoutCreate");
  PetscLayoutSetLocalSize(layout, out.n_owned);
  PetscLayoutSetBlockSize(layout, 1);
  check_petsc(PetscLayoutSetUp(layout), "PetscLayoutSetUp");
  std::vector<PetscInt> remote(out.global_node.begin(), out.global_node.end());
  for (int global : out.global_node)
    if (global < 0 || global >= total)
      throw std::logic_error("distributed mesh: a global node number " + std::to_string(global) + " outside [0, " +
                             std::to_string(total) + ")");
  PetscSF sf = nullptr;
  check_petsc(PetscSFCreate(PETSC_COMM_WORLD, &sf), "PetscSFCreate");
  check_petsc(PetscSFSetGraphLayout(sf, layout, n, nullptr, PETSC_COPY_VALUES, remote.data()), "PetscSFSetGraphLayout");
  PetscLayoutDestroy(&layout);
  check_petsc(PetscSFSetUp(sf), "PetscSFSetUp");
  out.shared = SharedNodes(sf, n, out.n_owned);
}

}  // namespace

MeshPart distribute_body_mesh(const Scene& scene, double max_gap, const BuildOptions& options,
                              const std::function<void(const Mesh& coarse)>& check_coarse) {
  const int ranks = world_size();
  CoarseMesh coarse;
  CoarseEntities entities;
  CoarseFacts facts;
  std::vector<Packet> packets;
  const CoarseMesh how = body_refinement(scene);
  if (world_rank() == 0) {
    coarse = coarse_body_mesh(scene, max_gap, options);
    if (how.refinements != coarse.refinements)
      throw std::logic_error("distributed mesh: the scene's refinement differs from its mesher's");
    const Mesh& mesh = coarse.mesh;
    if (check_coarse) check_coarse(mesh);
    facts.dim = mesh.dim;
    facts.order = mesh.order;
    facts.n_elements = mesh.n_elements();
    if (coarse.refinements > 0) {
      entities = number_coarse_entities(mesh);
    } else {
      entities.n_vertices = mesh.n_nodes();
      entities.n_cells = mesh.n_elements();
    }
    facts.totals = entities;
    facts.boundaries = names_of(mesh.boundaries);
    facts.regions = names_of(mesh.regions);
    facts.points = names_of(mesh.points);
    const std::vector<int> part = partition_elements(mesh, ranks);
    packets = pack_parts(mesh, entities, part, ranks, coarse.refinements > 0);
    coarse = CoarseMesh();  // the parts are all that is needed from here on
    entities = CoarseEntities();
  }
  checkpoint();  // the other ranks wait here for rank 0's outcome (a mesh file it cannot read)
  broadcast_facts(facts);
  const Packet packet = scatter_packets(packets);
  packets = {};
  CoarsePart part = unpack_part(packet, facts);

  MeshPart out;
  std::vector<long long> names;
  long long n_names = 0;
  {
    NodeParents parents;
    Mesh refined = refine_body_mesh(how, part.mesh, &parents);
    const CoarseLattice lattice(facts.dim, how.refinements, how.order, facts.totals);
    n_names = lattice.size();
    names = lattice.names(part.mesh, part.vertex, part.cell, part.edges, part.faces, parents);
    const long long face_factor = refined_children(facts.dim - 1, how.refinements);
    out.mesh = keep_own_children(refined, part, refined_children(facts.dim, how.refinements), face_factor, names);
  }
  checkpoint();
  part = CoarsePart();
  out.outer = std::move(out.mesh.boundaries[kOuter]);
  out.mesh.boundaries.erase(kOuter);
  long long elements = out.mesh.n_elements();
  MPI_Allreduce(&elements, &out.n_global_elements, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  number_nodes(out, names, n_names);
  return out;
}

}  // namespace contactqp::detail
