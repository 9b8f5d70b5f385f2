// The human summary of one solve: what was solved, how it ended, the certificate, the
// contact result against Hertz, and where the time went.
#include <cmath>
#include <cstdio>
#include <string>

#include "commands.hpp"

namespace contactqp::cli {

namespace {

std::string body_text(const Model& model) {
  const BodySpec& body = model.scene.body;
  std::string text;
  if (body.shape == "half_disc" || body.shape == "hemisphere")
    text = format("%s R = %g", body.shape.c_str(), body.radius);
  else if (body.shape == "rectangle")
    text = format("rectangle %g x %g", body.width, body.height);
  else if (body.shape == "box")
    text = format("box %g x %g x %g", body.width, body.depth, body.height);
  else
    text = "mesh " + body.file;
  if (model.dim == 2) {
    const double degrees = std::atan2(model.rotation(1, 0), model.rotation(0, 0)) * 180 / 3.14159265358979323846;
    if (degrees != 0) text += format(" rotated %g°", degrees);
  } else if (!model.rotation.isIdentity(0)) {
    text += " rotated";
  }
  return text;
}

std::string hertz_line(const char* label, const HertzComparison& h) {
  if (h.dim == 3)
    return format("  %s a = %.6g (error %+.2f%%), p0 = %.6g (error %+.2f%%), L2 pressure error %.2f%% (R = %.6g, %s)\n",
                  label, h.contact_radius, 100 * h.error_contact_radius, h.max_pressure, 100 * h.error_max_pressure,
                  100 * h.error_l2, h.radius, h.radius_source.c_str());
  return format("  %s b = %.6g (error %+.2f%%), p0 = %.6g (error %+.2f%%), L2 pressure error %.2f%% (R = %.6g, %s)\n",
                label, h.half_width, 100 * h.error_half_width, h.max_pressure, 100 * h.error_max_pressure,
                100 * h.error_l2, h.radius, h.radius_source.c_str());
}

// With friction: the zone's tangential force and stick zone, and Mindlin's where it applies.
std::string friction_lines(const FrictionZone& zone, int dim) {
  const char* size = dim == 2 ? "half-width" : "radius";
  std::string out = format("  friction     Q = %.6g, stick %s c = %.6g (%d stick, %d slip nodes)\n",
                           zone.tangential_force, size, zone.stick_size, zone.stick_nodes, zone.slip_nodes);
  if (const auto& m = zone.mindlin)
    out += format(
        "    mindlin    Q/(mu P) = %.3f: c = %.6g (error %+.2f%%), L2 traction error %.2f%% (mu = %g, beta = %.3f)\n",
        m->load_ratio, m->stick_size, 100 * m->error_stick_size, 100 * m->error_l2, m->coefficient, m->dundurs_beta);
  return out;
}

// One line per load step: its factors, how its solve ended, its contact's force and size.
std::string step_lines(const RunReport& report) {
  std::string out;
  const bool solid = report.model->dim == 3;
  for (size_t k = 0; k < report.steps.size(); ++k) {
    const StepReport& step = report.steps[k];
    std::string factors;
    for (const auto& [name, factor] : step.factors)
      factors += format("%s%s %g", factors.empty() ? "" : ", ", name.c_str(), factor);
    // The step's zone: the obstacles', or the first pair's in a scene of bodies without obstacles.
    double P = step.contact.total_force, size = solid ? step.contact.contact_radius : step.contact.half_width;
    double Q = step.contact.tangential_force, stick = step.contact.stick_size;
    if (step.contact.obstacles.empty() && !step.pairs.empty()) {
      const PairContact& pair = step.pairs.front();
      P = pair.total_force;
      size = solid ? pair.contact_radius : pair.half_width;
      Q = pair.friction ? pair.friction->tangential_force : 0.0;
      stick = pair.friction ? pair.friction->stick_size : 0.0;
    }
    out += format("  step %-7zu %s: %s, %d iterations, %.3g s; P = %.6g, %s = %.6g", k + 1, factors.c_str(),
                  to_string(step.status).c_str(), step.iterations, step.seconds, P, solid ? "a" : "b", size);
    out += report.qp->friction.empty() ? "\n" : format(", Q = %.6g, c = %.6g\n", Q, stick);
  }
  return out;
}

}  // namespace

std::string summary_table(const RunReport& report) {
  const Model& model = *report.model;
  const Scene& scene = model.scene;
  const SolveResult& result = report.result;
  const Certificate& c = report.certificate;
  std::string out;
  out += format("contactqp  %s\n", scene.source.c_str());
  const bool solid = model.dim == 3;
  out += format("  model        %s, %s%s, E = %g, nu = %g\n", to_string(scene.model).c_str(), body_text(model).c_str(),
                !scene.body.symmetry                          ? ""
                : symmetry_copies(scene.body, model.dim) == 4 ? " (quarter, symmetric)"
                : solid ? (" (half, symmetric about " + symmetry_name(scene.body) + " = 0)").c_str()
                        : " (half, symmetric)",
                scene.material.E, scene.material.nu);
  out += format("  mesh         %lld nodes, %lld %s (order %d), %lld DOFs, %lld contact candidates (gap <= %g)\n",
                report.size.nodes, report.size.elements, solid ? "tetrahedra" : "triangles", model.mesh.order,
                report.size.dofs, report.size.constraints, model.max_gap);
  std::string rho;
  auto it = result.diagnostics.find("rho");
  if (it != result.diagnostics.end()) {
    rho = format(", rho = %.4g", it->second);
    auto max = result.diagnostics.find("rho_max");
    if (max != result.diagnostics.end()) rho += format(" (%.3g rho_max)", it->second / max->second);
  }
  if (report.no_contact)
    out += format("  backend      none: contact rows dropped (--no-contact), one linear solve of K\n");
  else
    out += format("  backend      %s%s, tol %g\n", to_string(report.options.backend).c_str(), rho.c_str(),
                  report.options.tol);
  out += format("  status       %s after %d iterations: %s\n", to_string(result.status).c_str(), result.iterations,
                result.message.c_str());
  out += format("  certificate  KKT stationarity %.2e, primal %.2e, dual %.2e, complementarity %.2e%s\n",
                c.stationarity, c.primal_feasibility, c.dual_feasibility, c.complementarity,
                report.qp->friction.empty() ? "" : format(", tangential %.2e", c.tangential).c_str());
  if (c.dual_available)
    out += format("               J = %.10g, theta = %.10g, gap = %.2e (relative %.2e)\n", c.objective,
                  c.dual_objective, c.duality_gap, c.relative_gap);
  if (const auto& e = report.error_estimate)
    out += format(
        "  energy       strain energy E = %.10g, error estimate eta = %.4g (%.3g%% of sqrt(2E); recovery %.3g, "
        "contact %.3g)%s\n",
        e->strain_energy, e->estimate, 100 * e->relative, e->recovery, e->contact,
        e->force_relative ? format("; contact force error ~%.2g%%", 100 * *e->force_relative).c_str() : "");
  else if (report.strain_energy)
    out += format("  energy       strain energy E = %.10g (no error estimate)\n", *report.strain_energy);
  if (const auto& run = report.adaptive) {
    out += format("  adapt        target eta/sqrt(2E) <= %.3g%%: %s\n", 100 * run->spec.target,
                  run->met
                      ? format("met after %zu cycle%s", run->cycles.size(), run->cycles.size() == 1 ? "" : "s").c_str()
                      : ("not met: " + run->stop).c_str());
    // With friction two more columns: the tangential force Q and the stick zone c.
    const bool friction = !run->cycles.empty() && run->cycles.front().friction;
    out += format(
        "               cycle  elements      DOFs       eta  eta/sqrt(2E)  total force  max pressure  "
        "%s%s  iterations  time [s]\n",
        solid ? "radius a" : "  half b", friction ? "            Q  stick zone c" : "");
    for (std::size_t k = 0; k < run->cycles.size(); ++k) {
      const AdaptiveCycle& c = run->cycles[k];
      out += format("               %5zu %9lld %9lld %9.3g %12.3g%% %12.6g %13.6g %9.6g%s %11d %9.3g\n", k + 1,
                    c.elements, c.dofs, c.estimate, 100 * c.relative, c.total_force, c.max_pressure, c.zone,
                    friction ? format(" %12.6g %13.6g", c.tangential_force, c.stick_zone).c_str() : "", c.iterations,
                    c.seconds);
    }
  }
  const ContactSummary& contact = report.contact;
  for (const ModelBody& body : model.bodies)
    out += format("  body         %s: %s, E = %g, nu = %g, %d nodes\n", body.name.c_str(),
                  body.scene.body.shape.c_str(), body.scene.material.E, body.scene.material.nu, body.n_nodes);
  for (const PairContact& pair : report.pairs) {
    out += format("  pair         %s (nodes, %s%s) on %s: force on %s (%.6g, %.6g%s), action-reaction residual %.2e\n",
                  pair.node_side.c_str(), pair.side_rule.c_str(), pair.rows == "mortar" ? ", mortar rows" : "",
                  pair.face_side.c_str(), model.bodies[pair.node_body].name.c_str(), pair.force_on_node_body.x(),
                  pair.force_on_node_body.y(), solid ? format(", %.6g", pair.force_on_node_body.z()).c_str() : "",
                  pair.action_reaction);
    if (solid)
      out += format(
          "               radius a = %.6g (last node %.6g), area %.6g, max pressure %.6g (other side %.6g), %d nodes\n",
          pair.contact_radius, pair.contact_radius_last_node, pair.contact_area, pair.max_pressure,
          pair.face_max_pressure, pair.contact_nodes);
    else
      out += format(
          "               half-width b = %.6g (last node %.6g), max pressure %.6g (other side %.6g), %d nodes\n",
          pair.half_width, pair.half_width_last_node, pair.max_pressure, pair.face_max_pressure, pair.contact_nodes);
    if (pair.hertz) out += hertz_line("  hertz     ", *pair.hertz);
    if (pair.friction) out += friction_lines(*pair.friction, model.dim);
  }
  // The obstacles' line: always for one body; with bodies only when there are obstacles.
  if (model.bodies.empty() || !contact.obstacles.empty()) {
    if (solid)
      out += format(
          "  contact      force P = %.6g, radius a = %.6g (last node %.6g), area %.6g, max pressure p0 = %.6g, %d "
          "nodes\n",
          contact.total_force, contact.contact_radius, contact.contact_radius_last_node, contact.contact_area,
          contact.max_pressure, contact.contact_nodes);
    else
      out += format(
          "  contact      force P = %.6g, half-width b = %.6g (last node %.6g), max pressure p0 = %.6g, %d nodes\n",
          contact.total_force, contact.half_width, contact.half_width_last_node, contact.max_pressure,
          contact.contact_nodes);
  }
  if (report.hertz) out += hertz_line("hertz       ", *report.hertz);
  if (!contact.obstacles.empty() && contact.obstacles[contact.main_obstacle].friction)
    out += friction_lines(*contact.obstacles[contact.main_obstacle].friction, model.dim);
  if (report.boussinesq) {
    const PunchComparison& b = *report.boussinesq;
    out += format(
        "  boussinesq   P = 2 a E* delta = %.6g (a = %.6g, delta = %.6g): force error %+.2f%%, shape of p sqrt(a^2 - "
        "r^2) within %.2f%% for r <= 0.8 a\n",
        b.force, b.radius, b.approach, 100 * b.error_force, 100 * b.shape_error);
  }
  if (contact.obstacles.size() > 1) {
    for (const ObstacleContact& o : contact.obstacles) {
      out += format("  obstacle %-3d %s: force %.6g, %s %.6g, max pressure %.6g, %d nodes\n", o.obstacle,
                    scene.obstacles[o.obstacle].type().c_str(), o.total_force, solid ? "radius" : "half-width",
                    solid ? o.contact_radius : o.half_width, o.max_pressure, o.contact_nodes);
      if (const auto hertz = compare_with_hertz(model, o)) out += hertz_line("  hertz     ", *hertz);
    }
  }
  for (const Reaction& r : report.reactions) {
    // + 0.0 turns an exact −0 (a component that is zero by symmetry) into 0, which prints as "0".
    const Eigen::Vector3d f = r.force.array() + 0.0;
    if (r.rigid_surface()) {  // a force load: what its rigid surface carries and how far it moved
      std::string moved;
      for (int c = 0; c < model.dim; ++c)
        moved += (c ? ", " : "") + (r.displacement[c] ? format("%.6g", *r.displacement[c] + 0.0) : std::string("free"));
      out += format(
          "  rigid force  %s on \"%s\": (%s), moved by (%s)\n", r.load.c_str(), r.boundary.c_str(),
          solid ? format("%.6g, %.6g, %.6g", f.x(), f.y(), f.z()).c_str() : format("%.6g, %.6g", f.x(), f.y()).c_str(),
          moved.c_str());
      if (r.turns()) {  // and the moment it carries, how far it turned (radians; "held": not about that axis)
        std::string moment, turned;
        for (int a = solid ? 0 : 2; a < 3; ++a) {
          const bool first = a == (solid ? 0 : 2);
          moment += (first ? "" : ", ") + (r.rotation[a] ? format("%.6g", r.moment[a] + 0.0) : std::string("-"));
          turned += (first ? "" : ", ") + (r.rotation[a] ? format("%.6g", *r.rotation[a] + 0.0) : std::string("held"));
        }
        const Eigen::Vector3d c = r.about.array() + 0.0;
        out += format("  rigid moment %s about (%s): %s%s%s, turned by %s%s%s rad\n", r.load.c_str(),
                      solid ? format("%.6g, %.6g, %.6g", c.x(), c.y(), c.z()).c_str()
                            : format("%.6g, %.6g", c.x(), c.y()).c_str(),
                      solid ? "(" : "", moment.c_str(), solid ? ")" : "", solid ? "(" : "", turned.c_str(),
                      solid ? ")" : "");
      }
      continue;
    }
    out +=
        solid ? format("  reaction     %s on \"%s\": (%.6g, %.6g, %.6g)\n", r.load.c_str(), r.boundary.c_str(), f.x(),
                       f.y(), f.z())
              : format("  reaction     %s on \"%s\": (%.6g, %.6g)\n", r.load.c_str(), r.boundary.c_str(), f.x(), f.y());
  }
  for (const FloatingBody& body : report.floating) {
    std::string moved;
    for (int c = 0; c < model.dim; ++c)
      moved += (c ? ", " : "") + (body.translation[c] ? format("%.6g", *body.translation[c]) : std::string("held"));
    const std::string who = model.bodies.empty() ? "the body" : body.body;
    out += format("  floating     %s, held by its contacts: moved by (%s) on average\n", who.c_str(), moved.c_str());
  }
  out += step_lines(report);
  std::string times;
  for (const auto& [phase, seconds] : report.timings.phases())
    if (phase != "total") times += format("%s %.3f, ", phase.c_str(), seconds);
  out += format("  time [s]     %stotal %.3f\n", times.c_str(), report.timings.get("total"));
  return out;
}

}  // namespace contactqp::cli
