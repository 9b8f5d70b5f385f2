#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contactqp/io.hpp"

namespace contactqp {
namespace {

using nlohmann::json;

// NaN and Inf are not JSON: a number that is not finite is written as null.
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// The phases the README promises are always present (0 when a backend has no such phase).
const char* const kRequiredPhases[] = {"mesh", "assemble", "factorize", "solve", "total"};

json timings_json(const Timings& timings) {
  json out = json::object();
  for (const char* phase : kRequiredPhases) out[phase] = number(timings.get(phase));
  for (const auto& [phase, seconds] : timings.phases()) out[phase] = number(seconds);
  return out;
}

}  // namespace

std::string result_json(const RunReport& report) {
  const Model& model = *report.model;
  const QuadraticProgram& qp = *report.qp;
  const Certificate& c = report.certificate;
  json out;
  out["status"] = to_string(report.result.status);
  out["message"] = report.result.message;
  out["backend"] = report.no_contact ? "none" : to_string(report.options.backend);
  out["no_contact"] = report.no_contact;
  out["iterations"] = report.result.iterations;
  out["dofs"] = qp.n_dofs();
  out["constraints"] = qp.n_constraints();
  out["nodes"] = model.mesh.n_nodes();
  out["elements"] = model.mesh.n_elements();
  out["element_order"] = model.mesh.order;
  out["objective"] = number(c.objective);
  out["dual_objective"] = c.dual_available ? number(c.dual_objective) : json(nullptr);
  out["duality_gap"] = c.dual_available ? number(c.duality_gap) : json(nullptr);
  out["relative_duality_gap"] = c.dual_available ? number(c.relative_gap) : json(nullptr);
  out["kkt"] = {{"stationarity", number(c.stationarity)},
                {"primal_feasibility", number(c.primal_feasibility)},
                {"dual_feasibility", number(c.dual_feasibility)},
                {"complementarity", number(c.complementarity)},
                {"max", number(c.kkt_max())}};

  const ContactSummary& contact = report.contact;
  json profile = json::array();
  for (const ContactProfilePoint& point : contact.profile) profile.push_back({number(point.s), number(point.pressure)});
  out["contact"] = {{"total_force", number(contact.total_force)},
                    {"line_load", number(contact.line_load)},
                    {"half_width", number(contact.half_width)},
                    {"half_width_last_node", number(contact.half_width_last_node)},
                    {"max_pressure", number(contact.max_pressure)},
                    {"contact_nodes", contact.contact_nodes},
                    {"candidate_max_gap", number(model.max_gap)},
                    {"candidate_rule", model.max_gap_rule},
                    {"penetrating_non_candidates", contact.penetrating_non_candidates},
                    {"profile", profile}};
  if (report.hertz) {
    const HertzComparison& h = *report.hertz;
    out["hertz"] = {{"half_width", number(h.half_width)},
                    {"max_pressure", number(h.max_pressure)},
                    {"effective_modulus", number(h.effective_modulus)},
                    {"error_half_width", number(h.error_half_width)},
                    {"error_max_pressure", number(h.error_max_pressure)},
                    {"error_l2", number(h.error_l2)}};
  }
  json solver = {{"tol", number(report.options.tol)}, {"max_iterations", report.options.max_iterations}};
  for (const auto& [name, value] : report.result.diagnostics) solver[name] = number(value);
  out["solver"] = solver;
  // ρ and its limits also at top level, where the ρ studies read them.
  for (const char* key : {"rho", "rho_max", "rho_opt"}) {
    auto it = report.result.diagnostics.find(key);
    if (it != report.result.diagnostics.end()) out[key] = number(it->second);
  }
  out["timings"] = timings_json(report.timings);
  const Scene& scene = model.scene;
  out["scene"] = {{"source", scene.source},
                  {"model", to_string(scene.model)},
                  {"E", number(scene.material.E)},
                  {"nu", number(scene.material.nu)},
                  {"shape", scene.body.shape},
                  {"radius", number(scene.body.radius)},
                  {"symmetry", scene.body.symmetry},
                  {"thickness", number(scene.body.thickness)}};
  out["warnings"] = report.warnings;
  return out.dump(2) + "\n";
}

std::string profile_csv(const RunReport& report) {
  std::ostringstream out;
  out << std::setprecision(12);
  out << "s,pressure,force,hertz_pressure\n";
  for (const ContactProfilePoint& point : report.contact.profile) {
    out << point.s << ',' << point.pressure << ',' << point.force << ',';
    if (report.hertz) out << hertz_pressure(*report.hertz, point.s - report.contact.centre);
    out << '\n';
  }
  return out.str();
}

}  // namespace contactqp
