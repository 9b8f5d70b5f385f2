#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contact/contact.hpp"
#include "contactqp/io.hpp"

namespace contactqp {
namespace {

using nlohmann::json;

// NaN and Inf are not JSON: a number that is not finite is written as null.
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// The phases the README promises are always present (0 when a backend has no such phase).
const char* const kRequiredPhases[] = {"mesh", "assemble", "factorize", "solve", "total"};

// The first dim components of a vector.
json vector_json(const Eigen::Vector3d& v, int dim) {
  json out = json::array();
  for (int c = 0; c < dim; ++c) out.push_back(number(v[c]));
  return out;
}

json hertz_json(const HertzComparison& h) {
  if (h.dim == 3)
    return {{"radius", number(h.radius)},
            {"radius_source", h.radius_source},
            {"force", number(h.force)},
            {"contact_radius", number(h.contact_radius)},
            {"max_pressure", number(h.max_pressure)},
            {"effective_modulus", number(h.effective_modulus)},
            {"error_contact_radius", number(h.error_contact_radius)},
            {"error_max_pressure", number(h.error_max_pressure)},
            {"error_l2", number(h.error_l2)}};
  return {{"radius", number(h.radius)},
          {"radius_source", h.radius_source},
          {"half_width", number(h.half_width)},
          {"max_pressure", number(h.max_pressure)},
          {"effective_modulus", number(h.effective_modulus)},
          {"error_half_width", number(h.error_half_width)},
          {"error_max_pressure", number(h.error_max_pressure)},
          {"error_l2", number(h.error_l2)}};
}

json profile_json(const std::vector<ContactProfilePoint>& points) {
  json profile = json::array();
  for (const ContactProfilePoint& point : points) profile.push_back({number(point.s), number(point.pressure)});
  return profile;
}

json boussinesq_json(const PunchComparison& b) {
  return {{"radius", number(b.radius)},
          {"approach", number(b.approach)},
          {"effective_modulus", number(b.effective_modulus)},
          {"force", number(b.force)},
          {"error_force", number(b.error_force)},
          {"shape_error", number(b.shape_error)}};
}

json mindlin_json(const MindlinComparison& m) {
  const bool two_d = m.dim == 2;
  return {{"coefficient", number(m.coefficient)},
          {"normal_force", number(m.normal_force)},
          {"tangential_force", number(m.tangential_force)},
          {"load_ratio", number(m.load_ratio)},
          {"dundurs_beta", number(m.dundurs_beta)},
          {two_d ? "half_width" : "contact_radius", number(m.half_width)},
          {"max_pressure", number(m.max_pressure)},
          {two_d ? "stick_half_width" : "stick_radius", number(m.stick_size)},
          {two_d ? "stick_half_width_computed" : "stick_radius_computed", number(m.stick_size_computed)},
          {two_d ? "error_stick_half_width" : "error_stick_radius", number(m.error_stick_size)},
          {"error_l2", number(m.error_l2)},
          {"slip_displacement", number(m.slip_displacement)}};
}

// The friction entries of a contact zone, added to its object (obstacle, pair or the summary).
void add_friction(json& entry, const FrictionZone& zone, int dim) {
  entry["tangential_force"] = number(zone.tangential_force);
  entry["tangential_resultant"] = vector_json(zone.resultant, dim);
  entry[dim == 2 ? "stick_half_width" : "stick_radius"] = number(zone.stick_size);
  entry["stick_nodes"] = zone.stick_nodes;
  entry["slip_nodes"] = zone.slip_nodes;
  if (zone.mindlin) entry["mindlin"] = mindlin_json(*zone.mindlin);
}

json obstacles_json(const Model& model, const ContactSummary& contact) {
  json list = json::array();
  const int dim = model.dim;
  for (const ObstacleContact& o : contact.obstacles) {
    json entry = {{"type", model.scene.obstacles[o.obstacle].type()},
                  {"total_force", number(o.total_force)},
                  {"line_load", number(o.line_load)},
                  {"resultant", vector_json(o.resultant, dim)}};
    if (dim == 2) {
      entry["half_width"] = number(o.half_width);
      entry["half_width_last_node"] = number(o.half_width_last_node);
      entry["centre"] = number(o.centre);
    } else {
      entry["contact_radius"] = number(o.contact_radius);
      entry["contact_radius_last_node"] = number(o.contact_radius_last_node);
      entry["contact_area"] = number(o.contact_area);
      entry["centre"] = vector_json(o.centre_point, dim);
    }
    entry["max_pressure"] = number(o.max_pressure);
    entry["contact_nodes"] = o.contact_nodes;
    entry["profile"] = profile_json(o.profile);
    if (const auto hertz = compare_with_hertz(model, o)) entry["hertz"] = hertz_json(*hertz);
    if (o.friction) add_friction(entry, *o.friction, dim);
    list.push_back(entry);
  }
  return list;
}

json scene_json(const Model& model) {
  const Scene& scene = model.scene;
  constexpr double kDegrees = 180 / 3.14159265358979323846;
  json out = {{"source", scene.source},          {"model", to_string(scene.model)}, {"E", number(scene.material.E)},
              {"nu", number(scene.material.nu)}, {"shape", scene.body.shape},       {"symmetry", scene.body.symmetry}};
  if (symmetry_copies(scene.body, model.dim) == 2 && model.dim == 3) out["symmetry"] = symmetry_name(scene.body);
  if (model.dim == 2) {
    out["thickness"] = number(scene.body.thickness);
    out["rotate_degrees"] = number(std::atan2(model.rotation(1, 0), model.rotation(0, 0)) * kDegrees);
  } else {
    const Eigen::AngleAxisd turn(model.rotation);
    out["rotate_degrees"] = number(turn.angle() * kDegrees);
    out["axis"] = vector_json(turn.angle() == 0 ? Eigen::Vector3d::UnitZ() : turn.axis(), 3);
  }
  if (scene.body.shape == "half_disc" || scene.body.shape == "hemisphere") out["radius"] = number(scene.body.radius);
  if (scene.body.shape == "rectangle" || scene.body.shape == "box") {
    out["width"] = number(scene.body.width);
    if (scene.body.shape == "box") out["depth"] = number(scene.body.depth);
    out["height"] = number(scene.body.height);
  }
  if (scene.body.shape == "mesh") out["file"] = scene.body.file;
  return out;
}

json timings_json(const Timings& timings) {
  json out = json::object();
  for (const char* phase : kRequiredPhases) out[phase] = number(timings.get(phase));
  for (const auto& [phase, seconds] : timings.phases()) out[phase] = number(seconds);
  return out;
}

json reactions_json(const std::vector<Reaction>& reactions, int dim) {
  json supports = json::array();
  for (const Reaction& r : reactions) {
    json entry = {{"load", r.load}, {"boundary", r.boundary}, {"force", vector_json(r.force, dim)}};
    if (r.rigid_surface()) {  // a force load: how far its rigid surface moved (null: free)
      json moved = json::array();
      for (int c = 0; c < dim; ++c) moved.push_back(r.displacement[c] ? number(*r.displacement[c]) : json(nullptr));
      entry["displacement"] = moved;
    }
    if (r.turns()) {  // a moment: what it carries and how far it turned, as the load gives it (2D: about z)
      json moment = json::array(), turned = json::array();
      for (int a = 0; a < 3; ++a) {
        moment.push_back(r.rotation[a] ? number(r.moment[a]) : json(nullptr));
        turned.push_back(r.rotation[a] ? number(*r.rotation[a]) : json(nullptr));
      }
      entry["moment"] = dim == 2 ? moment[2] : moment;
      entry["rotation"] = dim == 2 ? turned[2] : turned;
      entry["about"] = vector_json(r.about, dim);
    }
    supports.push_back(entry);
  }
  return supports;
}

// Each load step's summary: its factors, how its solve went, its contact's force and size.
json steps_json(const RunReport& report, int dim) {
  json list = json::array();
  const char* size = dim == 2 ? "half_width" : "contact_radius";
  const char* stick = dim == 2 ? "stick_half_width" : "stick_radius";
  for (const StepReport& step : report.steps) {
    json factors = json::object();
    for (const auto& [name, factor] : step.factors) factors[name] = number(factor);
    json entry = {{"step", step.path},
                  {"factors", factors},
                  {"status", to_string(step.status)},
                  {"message", step.message},
                  {"iterations", step.iterations},
                  {"seconds", number(step.seconds)}};
    for (const auto& [name, value] : step.diagnostics) entry["diagnostics"][name] = number(value);
    const ContactSummary& c = step.contact;
    entry["total_force"] = number(c.total_force);
    entry[size] = number(dim == 2 ? c.half_width : c.contact_radius);
    if (!report.qp->friction.empty()) {
      entry["tangential_force"] = number(c.tangential_force);
      entry[stick] = number(c.stick_size);
      const auto& main = c.obstacles.empty() ? std::nullopt : c.obstacles[c.main_obstacle].friction;
      if (main && main->mindlin) entry["mindlin"] = mindlin_json(*main->mindlin);
    }
    json pairs = json::array();
    for (const PairContact& pair : step.pairs) {
      json p = {{"total_force", number(pair.total_force)},
                {"force_on_node_body", vector_json(pair.force_on_node_body, dim)},
                {size, number(dim == 2 ? pair.half_width : pair.contact_radius)}};
      if (pair.friction) {
        p["tangential_force"] = number(pair.friction->tangential_force);
        p[stick] = number(pair.friction->stick_size);
        if (pair.friction->mindlin) p["mindlin"] = mindlin_json(*pair.friction->mindlin);
      }
      pairs.push_back(p);
    }
    if (!pairs.empty()) entry["pairs"] = pairs;
    entry["reactions"] = reactions_json(step.reactions, dim);
    list.push_back(entry);
  }
  return list;
}

// The energy-error estimate (docs/estimate.md): η, its parts, η/‖u_h‖ and its cost; the
// indicators per element are in the ParaView file (error_indicator).
json error_estimate_json(const ErrorEstimate& e) {
  json out = {{"energy_norm", number(e.estimate)},
              {"relative", number(e.relative)},
              {"recovery", number(e.recovery)},
              {"contact", number(e.contact)},
              {"friction", number(e.friction)},
              {"max_indicator", number(e.max_indicator)},
              {"method", "recovered stress (nodal averages) + contact complementarity, penetration and friction terms"},
              {"seconds", number(e.seconds)}};
  if (e.force_relative) out["force_relative"] = number(*e.force_relative);
  return out;
}

// An adaptive run (docs/adaptive.md): its target, whether it was met, and every cycle.
json adaptive_json(const AdaptiveRun& run) {
  json cycles = json::array();
  for (const AdaptiveCycle& c : run.cycles) {
    json cycle = {{"elements", c.elements},
                  {"dofs", c.dofs},
                  {"energy_norm", number(c.estimate)},
                  {"relative", number(c.relative)},
                  {"strain_energy", number(c.strain_energy)},
                  {"total_force", number(c.total_force)},
                  {"max_pressure", number(c.max_pressure)},
                  {"zone", number(c.zone)},
                  {"iterations", c.iterations},
                  {"seconds", number(c.seconds)}};
    if (c.friction) {
      cycle["tangential_force"] = number(c.tangential_force);
      cycle["stick_zone"] = number(c.stick_zone);
    }
    cycles.push_back(cycle);
  }
  json out = {{"target", number(run.spec.target)},
              {"max_dofs", run.spec.max_dofs},
              {"max_cycles", run.spec.max_cycles},
              {"met", run.met},
              {"cycles", cycles}};
  if (!run.met) out["stop"] = run.stop;
  return out;
}

}  // namespace

std::string result_json(const RunReport& report) {
  const Model& model = *report.model;
  const QuadraticProgram& qp = *report.qp;  // its friction block (a distributed run's has none)
  const Certificate& c = report.certificate;
  json out;
  out["status"] = to_string(report.result.status);
  out["message"] = report.result.message;
  out["backend"] = report.no_contact ? "none" : to_string(report.options.backend);
  out["no_contact"] = report.no_contact;
  out["iterations"] = report.result.iterations;
  out["dofs"] = report.size.dofs;
  out["constraints"] = report.size.constraints;
  out["nodes"] = report.size.nodes;
  out["elements"] = report.size.elements;
  out["element_order"] = model.mesh.order;
  if (model.dim == 3) {
    out["dimension"] = 3;
    out["element_type"] = to_string(model.mesh.type());
  }
  out["objective"] = number(c.objective);
  out["dual_objective"] = c.dual_available ? number(c.dual_objective) : json(nullptr);
  out["duality_gap"] = c.dual_available ? number(c.duality_gap) : json(nullptr);
  out["relative_duality_gap"] = c.dual_available ? number(c.relative_gap) : json(nullptr);
  out["kkt"] = {{"stationarity", number(c.stationarity)},
                {"primal_feasibility", number(c.primal_feasibility)},
                {"dual_feasibility", number(c.dual_feasibility)},
                {"complementarity", number(c.complementarity)},
                {"max", number(c.kkt_max())}};
  if (!qp.friction.empty()) out["kkt"]["tangential"] = number(c.tangential);

  const ContactSummary& contact = report.contact;
  const int dim = model.dim;
  json& zone = out["contact"];
  zone = {
      {"total_force", number(contact.total_force)}, {"max_pressure", number(contact.max_pressure)},
      {"contact_nodes", contact.contact_nodes},     {"candidate_max_gap", number(model.max_gap)},
      {"candidate_rule", model.max_gap_rule},       {"penetrating_non_candidates", contact.penetrating_non_candidates},
      {"profile", profile_json(contact.profile)},  // 2D: [[s, p], ...]; 3D: [[r, p], ...] from the contact centre
      {"obstacles", obstacles_json(model, contact)}};
  if (dim == 2) {
    zone["line_load"] = number(contact.line_load);
    zone["half_width"] = number(contact.half_width);
    zone["half_width_last_node"] = number(contact.half_width_last_node);
  } else {
    zone["contact_area"] = number(contact.contact_area);
    zone["contact_radius"] = number(contact.contact_radius);
    zone["contact_radius_last_node"] = number(contact.contact_radius_last_node);
  }
  if (report.friction) {
    zone["tangential_force"] = number(contact.tangential_force);
    zone[dim == 2 ? "stick_half_width" : "stick_radius"] = number(contact.stick_size);
  }
  if (report.hertz) out["hertz"] = hertz_json(*report.hertz);
  if (report.boussinesq) out["boussinesq"] = boussinesq_json(*report.boussinesq);
  if (!model.bodies.empty()) {  // a scene with several bodies: each body and each pair
    json bodies = json::array();
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      const ModelBody& body = model.bodies[b];
      Eigen::Vector3d force = Eigen::Vector3d::Zero();  // the contact force on the body, every pair
      for (const PairContact& pair : report.pairs) {
        if (pair.node_body == static_cast<int>(b)) force += pair.force_on_node_body;
        if (pair.face_body == static_cast<int>(b)) force += pair.force_on_face_body;
      }
      bodies.push_back({{"name", body.name},
                        {"shape", body.scene.body.shape},
                        {"E", number(body.scene.material.E)},
                        {"nu", number(body.scene.material.nu)},
                        {"nodes", body.n_nodes},
                        {"elements", body.n_elements},
                        {"contact_force", vector_json(force, dim)}});
    }
    out["bodies"] = bodies;
    json pairs = json::array();
    for (const PairContact& pair : report.pairs) {
      json entry = {{"node_side", pair.node_side},
                    {"face_side", pair.face_side},
                    {"side_rule", pair.side_rule},
                    {"rows", pair.rows},
                    {"force_on_node_body", vector_json(pair.force_on_node_body, dim)},
                    {"force_on_face_body", vector_json(pair.force_on_face_body, dim)},
                    {"action_reaction_residual", number(pair.action_reaction)},
                    {"total_force", number(pair.total_force)},
                    {"max_pressure", number(pair.max_pressure)},
                    {"max_nodal_pressure", number(pair.max_nodal_pressure)},
                    {"face_max_pressure", number(pair.face_max_pressure)},
                    {"contact_nodes", pair.contact_nodes},
                    {"slipped_nodes", pair.slipped_nodes},
                    {"max_slip", number(pair.max_slip)},
                    {"profile", profile_json(pair.profile)},
                    {"face_profile", profile_json(pair.face_profile)}};
      if (dim == 2) {
        entry["line_load"] = number(pair.line_load);
        entry["half_width"] = number(pair.half_width);
        entry["half_width_last_node"] = number(pair.half_width_last_node);
      } else {
        entry["contact_area"] = number(pair.contact_area);
        entry["contact_radius"] = number(pair.contact_radius);
        entry["contact_radius_last_node"] = number(pair.contact_radius_last_node);
      }
      if (pair.hertz) entry["hertz"] = hertz_json(*pair.hertz);
      if (pair.friction) add_friction(entry, *pair.friction, dim);
      pairs.push_back(entry);
    }
    out["pairs"] = pairs;
  }
  out["reactions"] = reactions_json(report.reactions, dim);
  if (!report.floating.empty()) {  // bodies only their contacts hold (docs/bodies.md)
    json floating = json::array();
    for (const FloatingBody& body : report.floating) {
      json translation = json::array();
      for (int c = 0; c < dim; ++c)
        translation.push_back(body.translation[c] ? number(*body.translation[c]) : json(nullptr));
      floating.push_back({{"body", body.body}, {"translation", translation}});
    }
    out["floating"] = floating;
  }
  json solver = {{"tol", number(report.options.tol)}, {"max_iterations", report.options.max_iterations}};
  for (const auto& [name, value] : report.result.diagnostics) solver[name] = number(value);
  out["solver"] = solver;
  // An unbounded run's evidence (docs/extremes.md, "Problems without a solution"): d on the free
  // DOFs along which J falls without bound, in words and by the numbers that make it so.
  const VectorXd& direction = report.result.recession;
  if (direction.size() > 0 && direction.size() == qp.n_dofs() && qp.K.rows() == qp.n_dofs()) {
    const VectorXd& d = direction;
    const VectorXd Bd = qp.B * d;
    json recession = {{"f_dot_d", number(qp.f.dot(d))},
                      {"max_B_d", number(Bd.size() ? Bd.maxCoeff() : 0.0)},
                      {"max_abs_K_d", number(VectorXd(qp.K * d).cwiseAbs().maxCoeff())},
                      {"meaning",
                       "d (unit 2-norm on the free DOFs) with K d = 0, B d <= 0 and f.d > 0: the "
                       "energy falls without bound along u + t d"}};
    const std::string motion = describe_free_motion(model, d);
    if (!motion.empty()) recession["motion"] = motion;
    out["recession"] = recession;
  }
  // ρ and its limits also at top level, where the ρ studies read them.
  for (const char* key : {"rho", "rho_max", "rho_opt"}) {
    auto it = report.result.diagnostics.find(key);
    if (it != report.result.diagnostics.end()) out[key] = number(it->second);
  }
  // The Uzawa backends' spectrum estimate of S = B K⁻¹ Bᵀ, and which rows it covers.
  const auto& d = report.result.diagnostics;
  if (d.count("spectrum_rows") && d.count("lambda_max_S")) {
    const double lambda_min = d.count("lambda_min_S") ? d.at("lambda_min_S") : 0.0;
    out["spectrum_of_S"] = {
        {"rows", static_cast<int>(d.at("spectrum_rows"))},
        {"row_set", d.count("spectrum_all_rows") && d.at("spectrum_all_rows") == 0
                        ? "rows violated by the unconstrained solution K⁻¹f (the rows Uzawa's first step activates)"
                        : "every constraint row"},
        {"lambda_min", number(lambda_min)},
        {"lambda_max", number(d.at("lambda_max_S"))},
        {"condition_number", lambda_min > 0 ? number(d.at("lambda_max_S") / lambda_min) : json(nullptr)},
        {"method", "Lanczos with full reorthogonalisation, one solve with K per step"},
        {"solves", d.count("spectrum_solves") ? static_cast<int>(d.at("spectrum_solves")) : 0},
        {"seconds", number(report.timings.get("spectrum"))}};
  }
  if (!qp.friction.empty()) out["friction"] = {{"law", to_string(qp.friction.law)}};
  if (!report.steps.empty()) out["steps"] = steps_json(report, dim);
  out["timings"] = timings_json(report.timings);
  if (report.strain_energy) out["strain_energy"] = number(*report.strain_energy);
  if (const auto& e = report.error_estimate) out["error_estimate"] = error_estimate_json(*e);
  if (report.adaptive) out["adaptive"] = adaptive_json(*report.adaptive);
  out["scene"] = scene_json(model);
  out["warnings"] = report.warnings;
  return out.dump(2) + "\n";
}

namespace {

// With friction: the profile of every obstacle and every pair's node side, with the friction
// traction along the zone's tangential resultant (along the row's first tangent where the
// resultant vanishes), Mindlin's traction where it applies, the state and the node's position.
std::string friction_profile_csv(const RunReport& report) {
  std::ostringstream out;
  out << std::setprecision(12);
  const Model& model = *report.model;
  const FrictionFields& fields = *report.friction;
  const int dim = model.dim;
  out << (dim == 2 ? "s" : "r")
      << ",pressure,force,hertz_pressure,obstacle,pair,tangential_traction,mindlin_traction,state,x,y,z\n";
  auto rows = [&](const std::vector<ContactProfilePoint>& profile, const std::optional<HertzComparison>& hertz,
                  const FrictionZone& zone, double centre, int obstacle, int pair) {
    for (const ContactProfilePoint& point : profile) {
      const int i = point.row;
      const double x = dim == 2 ? point.s - centre : point.s;
      Eigen::Vector3d along = zone.resultant;
      if (!(zone.tangential_force > 0)) along = detail::row_tangents(model, model.candidates[i]).front();
      out << point.s << ',' << point.pressure << ',' << point.force << ',';
      if (hertz) out << hertz_pressure(*hertz, x);
      out << ',' << obstacle << ',' << pair << ',' << fields.traction[i].dot(along.normalized()) << ',';
      if (zone.mindlin) out << mindlin_traction(*zone.mindlin, x);
      const Eigen::Vector3d& p = model.mesh.nodes[point.node];
      out << ',' << fields.state[i] << ',' << p.x() << ',' << p.y() << ',' << p.z() << '\n';
    }
  };
  for (const ObstacleContact& contact : report.contact.obstacles)
    rows(contact.profile, compare_with_hertz(model, contact), *contact.friction, contact.centre, contact.obstacle, -1);
  for (const PairContact& pair : report.pairs)
    rows(pair.profile, pair.hertz, *pair.friction, pair.centre, -1, pair.pair);
  return out.str();
}

}  // namespace

std::string profile_csv(const RunReport& report) {
  if (report.friction) return friction_profile_csv(report);
  std::ostringstream out;
  out << std::setprecision(12);
  const Model& model = *report.model;
  // 2D: s along the obstacle surface; 3D: r, the distance from the contact centre.
  out << (model.dim == 2 ? "s" : "r") << ",pressure,force,hertz_pressure,obstacle\n";
  for (const ObstacleContact& contact : report.contact.obstacles) {
    const auto hertz = compare_with_hertz(model, contact);
    for (const ContactProfilePoint& point : contact.profile) {
      out << point.s << ',' << point.pressure << ',' << point.force << ',';
      if (hertz) out << hertz_pressure(*hertz, model.dim == 2 ? point.s - contact.centre : point.s);
      out << ',' << point.obstacle << '\n';
    }
  }
  return out.str();
}

}  // namespace contactqp
