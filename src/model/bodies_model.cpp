// A scene with several bodies as one model (docs/bodies.md): each body meshed in its own frame
// as a one-body scene would be — refined where the other bodies' surfaces come within the
// candidate distance — then placed, its boundary conditions and loads applied, and appended to
// one mesh. Nodes, elements and DOFs of a body are consecutive, so K is block-diagonal; the
// pairs add rows that couple two blocks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "model_parts.hpp"
#include "scene/obstacle_map.hpp"

namespace contactqp::detail {
namespace {

constexpr double kLoadGapFactor = 1.5;  // as for one body (model.cpp)

// A pair with friction presses along the common normal (n_face − n_node)/|…|, the line its
// partner point was found along, instead of the face's normal (docs/friction.md, "The pair's
// frame"). The friction's tangents are orthogonal to the common normal; a normal row along the
// face's normal, which leans off it by about r/R at a distance r from the first touch, would give
// the normal force a tangential share p·r/R that the friction must hold: two identical spheres'
// stick zone carried that odd share and slipped early on one side (q's L2 error 48 % against 13 %
// at Q/(μP) = 0.3 on scenes/mindlin-spheres.json). A frictionless pair (and μ = 0, s = 0) keeps
// the face's normal: today's rows and numbers.
void press_along_common_normal(const Mesh& mesh, Candidate& c) {
  if (!(c.common_normal.squaredNorm() > 0)) return;
  Eigen::Vector3d partner = Eigen::Vector3d::Zero();
  for (int j = 0; j < c.n_face_nodes; ++j) partner += c.weights[j] * mesh.nodes[c.face_nodes[j]];
  c.normal = c.common_normal;
  c.gap = (mesh.nodes[c.node] - partner).dot(c.normal);
}

// An InputError of a one-body step, named for the body: "body.mesh" becomes "bodies[1].mesh",
// "load[0]" "bodies[1].load[0]" (the body's loads are already named so).
[[noreturn]] void rethrow_for(const SceneBody& body, const InputError& error) {
  std::string field = error.field();
  if (field == "body" || field.rfind("body.", 0) == 0)
    field = body.path + field.substr(4);
  else if (field == "load" || field.rfind("contact", 0) == 0)
    field = body.path + "." + field;
  std::string message = error.what();
  const std::string prefix = error.field() + " ";
  if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
  throw InputError(field, message);
}

template <class Step>
auto for_body(const SceneBody& body, const Step& step) {
  try {
    return step();
  } catch (const InputError& error) {
    rethrow_for(body, error);
  }
}

// The largest prescribed displacement of a body's loads, or −1 with a force load.
double largest_push(const std::vector<LoadSpec>& loads) {
  double largest = 0;
  for (const LoadSpec& load : loads) {
    const DisplacementLoad* d = load.as<DisplacementLoad>();
    if (!d) return -1;
    largest =
        std::max(largest, std::hypot(d->value[0].value_or(0.0), d->value[1].value_or(0.0), d->value[2].value_or(0.0)));
  }
  return largest;
}

// The candidate distance for pairs and obstacles without their own max_gap: two bodies close
// by at most the sum of their pushes, so 1.5 × that sum; with a force load every facing node.
void choose_bodies_max_gap(const Scene& scene, Model& model) {
  // When every contact names its max_gap, the largest bounds the refined zone of the generated
  // shapes (as a one-body scene's contact.max_gap does), whatever the loads: a force scene and
  // the push that gives its force are then meshed alike.
  double given = 0;
  bool all_given = !scene.pairs.empty() || !scene.obstacle_contacts.empty();
  for (const ContactPair& pair : scene.pairs) {
    all_given = all_given && pair.max_gap.has_value();
    given = std::max(given, pair.max_gap.value_or(0.0));
  }
  for (const ObstacleContactSpec& entry : scene.obstacle_contacts) {
    all_given = all_given && entry.max_gap.has_value();
    given = std::max(given, entry.max_gap.value_or(0.0));
  }
  if (all_given) {
    model.max_gap = given;
    model.max_gap_rule = "the largest max_gap of the contacts";
    return;
  }
  double sum = 0;
  for (const SceneBody& body : scene.bodies) {
    const double push = largest_push(body.loads);
    if (push < 0) {  // forces give no displacement scale: every facing node
      model.max_gap = std::numeric_limits<double>::infinity();
      model.max_gap_rule = "every boundary node facing the other side (the loads include forces)";
      return;
    }
    sum += push;
  }
  model.max_gap = kLoadGapFactor * sum;
  model.max_gap_rule = "1.5 × the sum of the bodies' largest prescribed displacements";
}

ObstacleSpec to_local(const ObstacleSpec& obstacle, const BodyPlacement& placement, int dim) {
  return detail::mapped(
      obstacle, {[&](const Eigen::Vector3d& x) { return placement.to_local(x, dim); },
                 [&](const Eigen::Vector3d& d) { return placement.direction_to_local(d, dim); }, placement.mirror});
}

// A generated body's boundary as a rigid stand-in (global frame), to refine the other side of
// a pair where it may touch: a half disc's arc is its circle, a hemisphere's surface its
// sphere, a flat side its plane. None for a mesh body (mesh_stand_in() below has its boundary).
std::optional<ObstacleSpec> stand_in(const SceneBody& body, const std::string& boundary, int dim,
                                     const std::string& path) {
  const BodySpec& b = body.body;
  const BodyPlacement& at = body.placement;
  ObstacleSpec spec;
  spec.path = path;
  auto plane = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& outward) {
    spec.shape = PlaneObstacle{at.to_global(point, dim), at.direction_to_local(outward, dim)};
    return spec;
  };
  if (b.shape == "half_disc" && boundary == "arc") {
    spec.shape = CircleObstacle{at.to_global(Eigen::Vector3d(0, b.radius, 0), dim), b.radius};
    return spec;
  }
  if (b.shape == "hemisphere" && boundary == "surface") {
    spec.shape = SphereObstacle{at.to_global(Eigen::Vector3d(0, 0, b.radius), dim), b.radius};
    return spec;
  }
  const double w = b.width / 2, d = b.depth / 2, h = b.height;
  if (b.shape == "half_disc" && boundary == "top") return plane({0, b.radius, 0}, {0, 1, 0});
  if (b.shape == "hemisphere" && boundary == "top") return plane({0, 0, b.radius}, {0, 0, 1});
  if (b.shape == "rectangle" || b.shape == "box") {
    const int up = dim - 1;  // y in 2D, z in 3D
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), outward = Eigen::Vector3d::Zero();
    if (boundary == "bottom") {
      outward[up] = -1;
    } else if (boundary == "top") {
      point[up] = h;
      outward[up] = 1;
    } else if (boundary == "left" || boundary == "right") {
      point[0] = boundary == "left" ? -w : w;
      outward[0] = boundary == "left" ? -1 : 1;
    } else if (boundary == "front" || boundary == "back") {
      point[1] = boundary == "front" ? -d : d;
      outward[1] = boundary == "front" ? -1 : 1;
    } else {
      return std::nullopt;
    }
    return plane(point, outward);
  }
  return std::nullopt;
}

// A mesh body's boundary as the stand-in, from its placed mesh: in 2D the polyline of its edges
// (oriented with the mesh body on their left, so the other side lies on their right); none in
// 3D, or when the boundary is not one open chain.
std::optional<ObstacleSpec> mesh_stand_in(const Mesh& placed, const std::string& boundary, const std::string& path) {
  const auto found = placed.boundaries.find(boundary);
  if (placed.dim != 2 || found == placed.boundaries.end() || found->second.empty()) return std::nullopt;
  std::map<int, int> next;  // an edge's first vertex → its second
  std::set<int> ends;
  for (const BoundaryFace& face : found->second) {
    if (!next.emplace(face.nodes[0], face.nodes[1]).second) return std::nullopt;
    ends.insert(face.nodes[1]);
  }
  std::vector<int> starts;
  for (const auto& [from, to] : next)
    if (!ends.count(from)) starts.push_back(from);
  if (starts.size() != 1) return std::nullopt;  // a closed loop, or several pieces
  ProfileObstacle profile;
  profile.body_on_left = false;
  for (int node = starts.front();; node = next.at(node)) {
    profile.points.push_back(placed.nodes[node]);
    if (!next.count(node)) break;
  }
  if (profile.points.size() != found->second.size() + 1) return std::nullopt;
  ObstacleSpec spec;
  spec.path = path;
  spec.shape = profile;
  return spec;
}

// A body as a one-body scene of its own: its shape and material, the scene's model and source.
Scene own_scene(const Scene& scene, const SceneBody& body) {
  Scene local;
  local.source = scene.source;
  local.model = scene.model;
  local.material = body.material;
  local.body = body.body;
  return local;
}

// Reflects a placed body's mesh (y → −y in 2D, z → −z in 3D) and shifts it. A reflection turns
// every element inside out: flip them back and re-orient the boundary faces.
void place(Mesh& mesh, const BodyPlacement& placement) {
  const int dim = mesh.dim;
  if (placement.mirror) {
    for (Eigen::Vector3d& x : mesh.nodes) x[dim - 1] = -x[dim - 1];
    const int npe = mesh.nodes_per_element();
    for (int e = 0; e < mesh.n_elements(); ++e) flip_element(mesh.type(), mesh.elements.data() + e * npe);
    orient(mesh);
  }
  for (Eigen::Vector3d& x : mesh.nodes) x += placement.offset;
}

// The boundaries of body b that may touch something: of its pairs, then of its obstacle entries.
std::vector<std::string> touching_boundaries(const Scene& scene, int b) {
  std::vector<std::string> names;
  for (const ContactPair& pair : scene.pairs)
    for (int k = 0; k < 2; ++k)
      if (pair.body[k] == b) names.push_back(pair.boundary[k]);
  for (const ObstacleContactSpec& entry : scene.obstacle_contacts)
    if (entry.body == b) names.push_back(entry.boundary);
  return names;
}

void append(Model& model, const Model& part, const SceneBody& body, const Scene& one) {
  Mesh& mesh = model.mesh;
  const int node_offset = mesh.n_nodes(), element_offset = mesh.n_elements();
  const int dim = part.dim;
  ModelBody entry;
  entry.name = body.name;
  entry.scene = one;
  entry.placement = body.placement;
  entry.first_node = node_offset;
  entry.n_nodes = part.mesh.n_nodes();
  entry.first_element = element_offset;
  entry.n_elements = part.mesh.n_elements();
  model.bodies.push_back(entry);
  mesh.dim = part.mesh.dim;
  mesh.order = part.mesh.order;
  mesh.nodes.insert(mesh.nodes.end(), part.mesh.nodes.begin(), part.mesh.nodes.end());
  for (int v : part.mesh.elements) mesh.elements.push_back(v + node_offset);
  for (const auto& [name, faces] : part.mesh.boundaries) {
    auto& out = mesh.boundaries[body.name + "." + name];
    for (BoundaryFace face : faces) {
      for (int k = 0; k < face.n_nodes; ++k) face.nodes[k] += node_offset;
      out.push_back(face);
    }
  }
  for (const auto& [name, elements] : part.mesh.regions)
    for (int e : elements) mesh.regions[body.name + "." + name].push_back(e + element_offset);
  for (const auto& [name, nodes] : part.mesh.points)
    for (int n : nodes) mesh.points[body.name + "." + name].push_back(n + node_offset);
  model.element_body.insert(model.element_body.end(), part.mesh.n_elements(),
                            static_cast<int>(model.bodies.size()) - 1);
  for (int index : part.free_index) model.free_index.push_back(index < 0 ? -1 : index + model.n_free);
  for (RigidSurface surface : part.rigid_surfaces) {  // the body's loads follow the earlier bodies' in scene.loads
    surface.load += static_cast<int>(model.scene.loads.size());
    surface.column += model.n_free;
    for (int& node : surface.nodes) node += node_offset;
    model.rigid_surfaces.push_back(std::move(surface));
  }
  for (RigidRotation turn : part.rigid_rotations) {
    turn.load += static_cast<int>(model.scene.loads.size());
    turn.column += model.n_free;
    for (int& node : turn.nodes) node += node_offset;
    model.rigid_rotations.push_back(std::move(turn));
  }
  const int dof_offset = part.mesh.dim * node_offset;
  for (Lever lever : part.levers)  // the earlier bodies' DOFs come first: still sorted
    model.levers.push_back({lever.dof + dof_offset, lever.column + model.n_free, lever.weight});
  model.n_free += part.n_free;
  auto concatenate = [](Eigen::VectorXd& to, const Eigen::VectorXd& from) {
    Eigen::VectorXd joined(to.size() + from.size());
    joined << to, from;
    to = joined;
  };
  concatenate(model.prescribed, part.prescribed);
  concatenate(model.nodal_force, part.nodal_force);
  (void)dim;
}

}  // namespace

Model build_bodies_model(const Scene& scene, const BuildOptions& options) {
  Model model;
  const int dim = scene.dim();
  model.dim = dim;
  model.mesh.dim = dim;
  choose_bodies_max_gap(scene, model);
  model.scene = scene;
  model.scene.loads.clear();
  Stopwatch clock;
  double mesh_seconds = 0;
  // A mesh-file body is meshed as its file says, whatever it touches; it is read (or a .geo
  // meshed) once, when first needed: its own turn, or the other side of a pair asking for its
  // boundary as a stand-in.
  std::vector<std::optional<Mesh>> file_meshes(scene.bodies.size()), placed_file_meshes(scene.bodies.size());
  auto file_mesh = [&](int b) -> const Mesh& {
    if (!file_meshes[b]) {
      const SceneBody& body = scene.bodies[b];
      const Scene local = own_scene(scene, body);
      Stopwatch mesh_clock;
      file_meshes[b] = for_body(body, [&] { return mesh_body(local, model.max_gap, options); });
      mesh_seconds += mesh_clock.seconds();
    }
    return *file_meshes[b];
  };
  auto placed_file_mesh = [&](int b) -> const Mesh& {
    if (!placed_file_meshes[b]) {
      placed_file_meshes[b] = file_mesh(b);
      place(*placed_file_meshes[b], scene.bodies[b].placement);
    }
    return *placed_file_meshes[b];
  };
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const SceneBody& body = scene.bodies[b];
    const std::vector<std::string> touching = touching_boundaries(scene, static_cast<int>(b));
    if (touching.empty())
      throw InputError(body.path, "(\"" + body.name + "\") touches nothing: name one of its boundaries in contact");
    // The body as a one-body scene in its own frame, the obstacles and the other sides of its
    // pairs (as stand-ins) moved into that frame for the mesher's refinement.
    Scene local = own_scene(scene, body);
    local.loads = body.loads;
    local.contact.boundary = touching.front();
    for (const ObstacleSpec& obstacle : scene.obstacles)
      local.obstacles.push_back(to_local(obstacle, body.placement, dim));
    for (const ContactPair& pair : scene.pairs)
      for (int k = 0; k < 2; ++k)
        if (pair.body[k] == static_cast<int>(b)) {
          const int o = pair.body[1 - k];
          const SceneBody& other = scene.bodies[o];
          auto proxy = other.body.shape == "mesh" ? mesh_stand_in(placed_file_mesh(o), pair.boundary[1 - k], pair.path)
                                                  : stand_in(other, pair.boundary[1 - k], dim, pair.path);
          if (proxy) local.obstacles.push_back(to_local(*proxy, body.placement, dim));
        }
    Mesh mesh;
    Stopwatch mesh_clock;
    if (body.body.shape == "mesh") {
      // A later body may still need this one's boundary as its stand-in: place a copy first.
      const bool partner_later = std::any_of(scene.pairs.begin(), scene.pairs.end(), [&](const ContactPair& pair) {
        for (int k = 0; k < 2; ++k)
          if (pair.body[k] == static_cast<int>(b) && pair.body[1 - k] > static_cast<int>(b)) return true;
        return false;
      });
      if (partner_later) placed_file_mesh(static_cast<int>(b));
      file_mesh(static_cast<int>(b));
      mesh = std::move(*file_meshes[b]);
    } else {
      mesh = for_body(body, [&] { return mesh_body(local, model.max_gap, options); });
      mesh_seconds += mesh_clock.seconds();  // file_mesh() counts its own
    }
    for_body(body, [&] {
      check_mesh_names(local, mesh);
      for (const std::string& name : touching)
        if (!mesh.boundaries.count(name))
          throw InputError("contact", "names \"" + body.name + "." + name + "\": " + body.body.file +
                                          " has no boundary \"" + name + "\"");
      return 0;
    });
    place(mesh, body.placement);
    // Boundary conditions and loads in the global frame, on the placed mesh.
    Scene one = local;
    one.obstacles = scene.obstacles;
    Model part;
    part.scene = one;
    part.mesh = std::move(mesh);
    part.dim = dim;
    // Whether the body is held (by its prescribed displacements, or by its contacts) is decided
    // once every candidate row is known, below.
    for_body(body, [&] {
      apply_displacement_conditions(part, one, Eigen::Matrix3d::Identity());
      return 0;
    });
    const std::vector<int> point_nodes = point_load_nodes(one, part.mesh, model.warnings);
    part.nodal_force = nodal_forces(one, part.mesh, point_nodes);
    const int first_node = model.mesh.n_nodes();
    if (!scene.steps.empty())  // the body's loads' shares, their DOFs moved to the body's block
      for (LoadShare& share : load_shares(part, point_nodes)) {
        for (auto& entry : share.prescribed) entry.first += dim * first_node;
        model.load_shares.push_back(std::move(share));
      }
    append(model, part, body, one);
    for (LoadSpec load : body.loads) {  // the scene's loads, named by the merged mesh's boundaries
      if (std::string* boundary = load.boundary()) *boundary = body.name + "." + *boundary;
      model.scene.loads.push_back(load);
    }
    for (const ObstacleContactSpec& entry : scene.obstacle_contacts) {
      if (entry.body != static_cast<int>(b)) continue;
      std::vector<Candidate> found =
          select_candidates(part.mesh, scene.obstacles, entry.boundary, entry.max_gap.value_or(model.max_gap));
      for (Candidate& c : found) {
        c.node += first_node;
        c.body = static_cast<int>(b);
        model.candidates.push_back(c);
      }
    }
  }
  model.timings.add("mesh", mesh_seconds);

  for (size_t p = 0; p < scene.pairs.size(); ++p) {
    const ContactPair& pair = scene.pairs[p];
    const double max_gap = pair.max_gap.value_or(model.max_gap);
    const std::string side[2] = {scene.bodies[pair.body[0]].name + "." + pair.boundary[0],
                                 scene.bodies[pair.body[1]].name + "." + pair.boundary[1]};
    // The nodes go on the finer side: its nodes resolve the pressure, and the coarser side's
    // faces cannot pass between them (one pass: rows from both sides would over-constrain,
    // docs/bodies.md). A tie keeps the first side written.
    PairSides sides;
    const double size[2] = {smallest_face_size(model.mesh, side[0]), smallest_face_size(model.mesh, side[1])};
    sides.node_side = size[1] < size[0] * (1 - 1e-6) ? 1 : 0;
    sides.rule = size[0] == size[1] || std::abs(size[0] - size[1]) <= 1e-6 * size[0] ? "equal meshes: the first side"
                                                                                     : "the finer mesh";
    sides.node_face_size = size[sides.node_side];
    sides.face_face_size = size[1 - sides.node_side];
    model.pair_sides.push_back(sides);
    const int n = sides.node_side;
    std::vector<Candidate> found = select_pair_candidates(model.mesh, side[n], side[1 - n], max_gap);
    if (pair.rows == PairRows::Mortar) make_mortar_rows(model.mesh, side[n], side[1 - n], found);
    const double depth = std::isfinite(max_gap) ? max_gap : 0.0;
    const bool frictional = pair.friction && (pair.friction->coefficient > 0 || pair.friction->threshold > 0);
    for (Candidate& c : found) {
      if (frictional) press_along_common_normal(model.mesh, c);
      c.pair = static_cast<int>(p);
      c.obstacle = -1;
      c.body = pair.body[n];
      c.other_body = pair.body[1 - n];
      // Bodies that start inside each other beyond the candidate distance are a mistake of the
      // scene (a wrong offset), not a contact to resolve.
      const double tolerance = depth + 1e-9 * sides.face_face_size;
      if (c.gap < -tolerance)
        throw InputError(pair.path, "= [\"" + side[0] + "\", \"" + side[1] +
                                        "\"]: the bodies overlap at the start: node " + std::to_string(c.node) +
                                        " at " + format_point(model.mesh.nodes[c.node], dim) + " lies " +
                                        format_value(-c.gap) + " inside \"" + scene.bodies[c.other_body].name +
                                        "\" (more than max_gap = " + format_value(depth) + ")");
      model.candidates.push_back(c);
    }
  }
  if (!scene.obstacle_contacts.empty())
    model.scene.contact.boundary =
        scene.bodies[scene.obstacle_contacts.front().body].name + "." + scene.obstacle_contacts.front().boundary;
  remove_prescribed_candidates(model);
  // Rigid motions a body's prescribed displacements leave free: held by its contacts (with the
  // obstacles, or with the other bodies through the pairs' rows), or refused naming the body when
  // its load drives one that no row sees (docs/extremes.md). Bodies have no transform: the
  // scene's frame is the global one.
  const Eigen::MatrixXd free_motions =
      motions_held_by_contact(model, [&] { return Eigen::VectorXd(model.nodal_force + rigid_surface_forces(model)); });
  if (free_motions.cols() > 0) model.free_modes = free_modes_on_dofs(model, free_motions);
  // Each load's nodal forces over the whole mesh: zero outside its body's block.
  for (size_t l = 0, b = 0, in_body = 0; l < model.load_shares.size(); ++l, ++in_body) {
    while (in_body >= scene.bodies[b].loads.size()) {
      ++b;
      in_body = 0;
    }
    Eigen::VectorXd whole = Eigen::VectorXd::Zero(model.prescribed.size());
    whole.segment(dim * model.bodies[b].first_node, model.load_shares[l].nodal_force.size()) =
        model.load_shares[l].nodal_force;
    model.load_shares[l].nodal_force = whole;
  }
  model.timings.add("model", clock.seconds() - mesh_seconds);
  return model;
}

}  // namespace contactqp::detail
