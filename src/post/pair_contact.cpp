// Post-processing of the contact between two bodies: the force on each (action and reaction),
// the pressure on each side, the zone's size, small-slip check, and Hertz for two cylinders
// (2D) or two spheres (3D): 1/R = 1/R₁ + 1/R₂, 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "contact/contact.hpp"
#include "contactqp/post.hpp"
#include "fitted_curvature.hpp"
#include "qp/pi.hpp"

namespace contactqp {
namespace {

// The curvature of a generated body's boundary: 1/R for a half disc's arc or a hemisphere's
// surface, 0 for a flat side; nullopt for a mesh body (fitted below) or a curved top.
std::optional<double> boundary_curvature(const BodySpec& body, const std::string& boundary) {
  if ((body.shape == "half_disc" && boundary == "arc") || (body.shape == "hemisphere" && boundary == "surface"))
    return 1.0 / body.radius;
  if (body.shape == "rectangle" || body.shape == "box" || (body.shape != "mesh" && boundary == "top")) return 0.0;
  return std::nullopt;
}

// A mesh body's side of a pair, fitted through the nodes that carry the pair's force (their
// initial positions): the node side's loaded nodes, or the faces those nodes press on. A
// candidate's normal is its face's outward one, from the face side towards the node side.
std::optional<double> fitted_side_curvature(const Model& model, const PairContact& contact, bool node_side) {
  std::map<int, const Candidate*> row_of;
  for (const Candidate& c : model.candidates)
    if (c.pair == contact.pair) row_of[c.node] = &c;
  double most = 1e-300;
  for (const ContactProfilePoint& p : contact.profile) most = std::max(most, p.force);
  std::vector<Eigen::Vector3d> points;
  std::set<int> taken;
  Eigen::Vector3d towards = Eigen::Vector3d::Zero();
  for (const ContactProfilePoint& p : contact.profile) {
    const auto row = row_of.find(p.node);
    if (!(p.force > 1e-8 * most) || row == row_of.end()) continue;
    const Candidate& c = *row->second;
    towards += node_side ? -c.normal : c.normal;
    if (node_side) {
      points.push_back(model.mesh.nodes[p.node]);
      continue;
    }
    // A mortar row lists nodes of its own side too: only the face side's are fitted.
    for (int j = 0; j < c.n_face_nodes; ++j)
      if (model.body_of_node(c.face_nodes[j]) == contact.face_body && taken.insert(c.face_nodes[j]).second)
        points.push_back(model.mesh.nodes[c.face_nodes[j]]);
  }
  return fitted_curvature(points, model.dim, towards);
}

// 1/E* of one body: (1 − ν²)/E in plane strain and solid, 1/E in plane stress.
double compliance(const Scene& scene) {
  const double E = scene.material.E, nu = scene.material.nu;
  return scene.model == ElasticModel::PlaneStress ? 1.0 / E : (1 - nu * nu) / E;
}

// s of a point for the profile: along the tangent t (2D), or r from the centre across n (3D).
double coordinate(const Eigen::Vector3d& x, int dim, const Eigen::Vector3d& tangent, const Eigen::Vector3d& centre,
                  const Eigen::Vector3d& normal) {
  if (dim == 2) return x.dot(tangent);
  const Eigen::Vector3d d = x - centre;
  return (d - d.dot(normal) * normal).norm();
}

std::optional<HertzComparison> compare_pair_with_hertz(const Model& model, const PairContact& contact) {
  const ModelBody& a = model.bodies[contact.node_body];
  const ModelBody& b = model.bodies[contact.face_body];
  const ContactPair& pair = model.scene.pairs[contact.pair];
  const int node_side = model.pair_sides[contact.pair].node_side;
  auto ka = boundary_curvature(a.scene.body, pair.boundary[node_side]);
  auto kb = boundary_curvature(b.scene.body, pair.boundary[1 - node_side]);
  const bool fitted = !ka || !kb;
  if (!ka && a.scene.body.shape == "mesh") ka = fitted_side_curvature(model, contact, true);
  if (!kb && b.scene.body.shape == "mesh") kb = fitted_side_curvature(model, contact, false);
  const int dim = model.dim;
  // Two flat sides (or a curvature lost in the fit's noise) are not Hertz's problem.
  const double zone = dim == 3 ? contact.contact_radius : contact.half_width;
  if (!ka || !kb || !(*ka + *kb > 0) || (fitted && (*ka + *kb) * std::max(zone, 1e-300) < 1e-6)) return std::nullopt;
  HertzComparison hertz;
  hertz.dim = dim;
  hertz.radius = 1.0 / (*ka + *kb);
  hertz.radius_source = fitted ? "bodies' radii, a mesh body's fitted" : "bodies' radii";
  hertz.effective_modulus = 1.0 / (compliance(a.scene) + compliance(b.scene));
  const double R = hertz.radius, E = hertz.effective_modulus;
  const double P =
      dim == 2 ? contact.force_on_node_body.norm() / model.scene.body.thickness : contact.force_on_node_body.norm();
  if (!(P > 0)) return std::nullopt;
  hertz.force = P;
  const auto& profile = contact.profile;
  if (dim == 2) {
    hertz.half_width = std::sqrt(4 * P * R / (kPi * E));
    hertz.max_pressure = 2 * P / (kPi * hertz.half_width);
    hertz.error_half_width = (contact.half_width - hertz.half_width) / hertz.half_width;
    // L2 error by the trapezoidal rule of the squared difference over the node profile.
    double error = 0, reference = 0;
    for (size_t k = 0; k + 1 < profile.size(); ++k) {
      const double h = profile[k + 1].s - profile[k].s;
      auto d2 = [&](const ContactProfilePoint& p) {
        const double d = p.pressure - hertz_pressure(hertz, p.s - contact.centre);
        return d * d;
      };
      auto h2 = [&](const ContactProfilePoint& p) { return std::pow(hertz_pressure(hertz, p.s - contact.centre), 2); };
      error += 0.5 * h * (d2(profile[k]) + d2(profile[k + 1]));
      reference += 0.5 * h * (h2(profile[k]) + h2(profile[k + 1]));
    }
    hertz.error_l2 = reference > 0 ? std::sqrt(error / reference) : 0.0;
  } else {
    hertz.contact_radius = std::cbrt(3 * P * R / (4 * E));
    hertz.max_pressure = 3 * P / (2 * kPi * hertz.contact_radius * hertz.contact_radius);
    hertz.error_contact_radius = (contact.contact_radius - hertz.contact_radius) / hertz.contact_radius;
    std::map<int, double> tributary;
    for (const Candidate& c : model.candidates)
      if (c.pair == contact.pair) tributary[c.node] = c.tributary;
    double error = 0;
    for (const ContactProfilePoint& point : profile) {
      const double d = point.pressure - hertz_pressure(hertz, point.s);
      error += tributary[point.node] * d * d;
    }
    const double a0 = hertz.contact_radius;
    const double reference = kPi * a0 * a0 * hertz.max_pressure * hertz.max_pressure / 2 / mirror_copies(model);
    hertz.error_l2 = std::sqrt(error / reference);
  }
  hertz.error_max_pressure = (contact.max_pressure - hertz.max_pressure) / hertz.max_pressure;
  return hertz;
}

}  // namespace

Eigen::VectorXd contact_nodal_forces(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda) {
  const int dim = model.dim;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(dim * model.mesh.n_nodes());
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& c = model.candidates[i];
    if (c.pair < 0) {
      const Eigen::Vector3d n = detail::project(model.scene.obstacles[c.obstacle], model.mesh.nodes[c.node]).normal;
      force.segment(dim * c.node, dim) += lambda[i] * n.head(dim);
      continue;
    }
    force.segment(dim * c.node, dim) += lambda[i] * c.normal.head(dim);
    for (int j = 0; j < c.n_face_nodes; ++j)
      force.segment(dim * c.face_nodes[j], dim) -= lambda[i] * c.weights[j] * c.normal.head(dim);
  }
  return force;
}

std::vector<PairContact> summarize_pairs(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                         const Eigen::VectorXd& lambda) {
  std::vector<PairContact> out;
  const int dim = model.dim;
  const bool symmetry = model.scene.body.symmetry;
  const double copies = mirror_copies(model);
  const Eigen::Vector3d axis = dim == 2 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const std::vector<double> pressure = nodal_pressures(model, qp, lambda);
  const double lambda_max = lambda.size() ? lambda.maxCoeff() : 0.0;
  const double loaded = 1e-8 * lambda_max;
  for (size_t p = 0; p < model.scene.pairs.size(); ++p) {
    const ContactPair& pair = model.scene.pairs[p];
    const PairSides& sides = model.pair_sides[p];
    PairContact contact;
    contact.pair = static_cast<int>(p);
    const int n = sides.node_side;
    contact.node_body = pair.body[n];
    contact.face_body = pair.body[1 - n];
    contact.node_side = model.bodies[pair.body[n]].name + "." + pair.boundary[n];
    contact.face_side = model.bodies[pair.body[1 - n]].name + "." + pair.boundary[1 - n];
    contact.side_rule = sides.rule;
    contact.rows = pair.rows == PairRows::Mortar ? "mortar" : "node_to_face";
    // Forces on each body from the rows' nodal forces, summed by the body each node is in.
    std::vector<int> rows;
    std::map<int, double> face_force;  // face node → Σ_i λ_i N_j(ξ_i)
    Eigen::Vector3d on_node = Eigen::Vector3d::Zero(), on_face = Eigen::Vector3d::Zero();
    for (int i = 0; i < qp.n_constraints(); ++i) {
      const Candidate& c = model.candidates[i];
      if (c.pair != contact.pair) continue;
      rows.push_back(i);
      on_node += lambda[i] * c.normal;
      for (int j = 0; j < c.n_face_nodes; ++j) {
        // A mortar row's terms on its own side (a quadratic face's) sum to zero: the force λ_i
        // n is the node side's, what the other side's terms carry the face side's.
        if (model.body_of_node(c.face_nodes[j]) != contact.face_body) continue;
        on_face -= lambda[i] * c.weights[j] * c.normal;
        face_force[c.face_nodes[j]] += lambda[i] * c.weights[j];
      }
      contact.total_force += copies * lambda[i];
    }
    // The mirrored parts add along the cuts and cancel across them.
    on_node = whole_body_sum(model, on_node);
    on_face = whole_body_sum(model, on_face);
    contact.force_on_node_body = on_node;
    contact.force_on_face_body = on_face;
    const double scale = std::max(on_node.norm(), on_face.norm());
    contact.action_reaction = scale > 0 ? (on_node + on_face).norm() / scale : 0.0;
    contact.line_load = on_node.norm() / thickness;
    // The mean contact normal (into the node side) and, in 2D, the tangent s runs along.
    Eigen::Vector3d normal = on_node.norm() > 0 ? Eigen::Vector3d(on_node.normalized()) : axis;
    if (!(on_node.norm() > 0) && !rows.empty()) normal = model.candidates[rows.front()].normal;
    contact.normal = normal;
    Eigen::Vector3d tangent(normal.y(), -normal.x(), 0.0);
    if (tangent.x() < 0) tangent = -tangent;
    // The centre of pressure (on the axis with symmetry).
    double sum = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    for (int i : rows) {
      sum += lambda[i];
      first += lambda[i] * model.mesh.nodes[model.candidates[i].node];
    }
    Eigen::Vector3d centre = sum > 0 ? Eigen::Vector3d(first / sum) : Eigen::Vector3d::Zero();
    centre = mirror_mean(model, centre);
    double second = 0;
    for (int i : rows) {
      const Candidate& c = model.candidates[i];
      ContactProfilePoint point;
      point.node = c.node;
      point.row = i;
      point.force = lambda[i];
      point.pressure = pressure[i];
      point.s = coordinate(model.mesh.nodes[c.node], dim, tangent, centre, normal);
      contact.profile.push_back(point);
      contact.max_nodal_pressure = std::max(contact.max_nodal_pressure, point.pressure);
      if (lambda[i] > loaded && lambda_max > 0) {
        ++contact.contact_nodes;
        contact.contact_area += copies * c.tributary;
      }
    }
    std::sort(contact.profile.begin(), contact.profile.end(),
              [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
    contact.max_pressure = contact.max_nodal_pressure;
    if (dim == 2) {
      // Patch averages along the whole body's profile. With symmetry that is the half model's
      // profile mirrored about s = 0: each node at s > 0 gets its image at −s, and the node on
      // the symmetry plane — which carries half of the whole body's force there over half its
      // tributary — counts with its image as one node of twice the force and length.
      std::map<int, double> tributary;
      for (int i : rows) tributary[model.candidates[i].node] = model.candidates[i].tributary * thickness;
      const auto& pr = contact.profile;
      double s_scale = 0;
      for (const ContactProfilePoint& point : pr) s_scale = std::max(s_scale, std::abs(point.s));
      std::vector<double> force, width;  // per node of the whole profile, in order of s
      if (symmetry)
        for (size_t k = pr.size(); k-- > 0;)
          if (pr[k].s > 1e-12 * s_scale) {
            force.push_back(pr[k].force);
            width.push_back(tributary[pr[k].node]);
          }
      for (const ContactProfilePoint& point : pr) {
        const double copies_here = symmetry && std::abs(point.s) <= 1e-12 * s_scale ? 2.0 : 1.0;
        force.push_back(copies_here * point.force);
        width.push_back(copies_here * tributary[point.node]);
      }
      double smoothed_max = 0;
      for (size_t k = 0; k < force.size(); ++k) {
        double f = force[k], w = width[k];
        if (k > 0) {
          f += force[k - 1];
          w += width[k - 1];
        }
        if (k + 1 < force.size()) {
          f += force[k + 1];
          w += width[k + 1];
        }
        if (w > 0) smoothed_max = std::max(smoothed_max, f / w);
      }
      contact.max_pressure = smoothed_max;
      contact.centre = symmetry || !(sum > 0) ? 0.0 : centre.dot(tangent);
      for (const ContactProfilePoint& point : contact.profile) {
        const double d = point.s - contact.centre;
        second += point.force * d * d;
        if (point.force > loaded) contact.half_width_last_node = std::max(contact.half_width_last_node, std::abs(d));
      }
      contact.half_width = sum > 0 ? 2.0 * std::sqrt(second / sum) : 0.0;
      contact.contact_area = 0;
    } else {
      for (const ContactProfilePoint& point : contact.profile) {
        second += point.force * point.s * point.s;
        if (point.force > loaded)
          contact.contact_radius_last_node = std::max(contact.contact_radius_last_node, point.s);
      }
      contact.contact_radius = sum > 0 ? std::sqrt(2.5 * second / sum) : 0.0;
    }
    // The face side's pressure: its nodes' shares over their tributary lengths or areas.
    const detail::BoundaryNodeGeometry face_geometry = detail::boundary_geometry(model.mesh, contact.face_side);
    for (size_t k = 0; k < face_geometry.nodes.size(); ++k) {
      const auto it = face_force.find(face_geometry.nodes[k]);
      if (it == face_force.end()) continue;
      ContactProfilePoint point;
      point.node = it->first;
      point.force = it->second;
      const double w = face_geometry.tributary[k] * thickness;
      point.pressure = w > 0 ? it->second / w : 0.0;
      point.s = coordinate(model.mesh.nodes[it->first], dim, tangent, centre, normal);
      contact.face_profile.push_back(point);
      contact.face_max_pressure = std::max(contact.face_max_pressure, point.pressure);
    }
    std::sort(contact.face_profile.begin(), contact.face_profile.end(),
              [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
    // Small slip: is a loaded node still over (a neighbour of) the face its row was made on?
    const auto faces = model.mesh.boundaries.find(contact.face_side);
    std::vector<Eigen::Vector3d> moved = model.mesh.nodes;
    for (int k = 0; k < model.mesh.n_nodes(); ++k) moved[k].head(dim) += displacement.segment(dim * k, dim);
    for (int i : rows) {
      const Candidate& c = model.candidates[i];
      if (!(lambda[i] > loaded) || faces == model.mesh.boundaries.end()) continue;
      Eigen::Vector3d relative = Eigen::Vector3d::Zero();
      relative.head(dim) = displacement.segment(dim * c.node, dim);
      for (int j = 0; j < c.n_face_nodes; ++j)
        relative.head(dim) -= c.weights[j] * displacement.segment(dim * c.face_nodes[j], dim);
      const double slip = (relative - relative.dot(c.normal) * c.normal).norm();
      contact.max_slip = std::max(contact.max_slip, slip);
      const detail::ClosestFace now = detail::closest_face(moved, faces->second, dim, moved[c.node]);
      if (now.face < 0) continue;
      const BoundaryFace& was = faces->second[c.face];
      const BoundaryFace& is = faces->second[now.face];
      bool shares = false;
      for (int a = 0; a < was.n_nodes; ++a)
        for (int b = 0; b < is.n_nodes; ++b) shares = shares || was.nodes[a] == is.nodes[b];
      if (!shares) ++contact.slipped_nodes;
    }
    contact.hertz = compare_pair_with_hertz(model, contact);
    out.push_back(std::move(contact));
  }
  return out;
}

}  // namespace contactqp
