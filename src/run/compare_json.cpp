// The comparison as JSON (contactqp compare --json). Numbers that are not finite are null.
#include <cmath>
#include <nlohmann/json.hpp>

#include "contactqp/run.hpp"

namespace contactqp {
namespace {

using nlohmann::json;

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json number(const std::optional<double>& x) { return x ? number(*x) : json(nullptr); }

// 2D runs report the half-width b, 3D runs the contact radius a.
json run_json(const BackendRun& run, double linear_solve_seconds, int dim) {
  const Certificate& c = run.certificate;
  json timings = json::object();
  for (const auto& [phase, seconds] : run.result.timings.phases()) timings[phase] = number(seconds);
  json out = {{"backend", to_string(run.backend)},
              {"status", to_string(run.result.status)},
              {"message", run.result.message},
              {"iterations", run.result.iterations},
              {"seconds", number(run.result.timings.get("total"))},
              {"seconds_in_linear_solves", number(run.result.timings.get("total") / linear_solve_seconds)},
              {"objective", number(c.objective)},
              {"dual_objective", c.dual_available ? number(c.dual_objective) : json(nullptr)},
              {"duality_gap", c.dual_available ? number(c.duality_gap) : json(nullptr)},
              {"relative_duality_gap", c.dual_available ? number(c.relative_gap) : json(nullptr)},
              {"kkt_max", number(c.kkt_max())},
              {"rel_diff_u", number(run.rel_diff_u)},
              {"rel_diff_lambda", number(run.rel_diff_lambda)},
              {dim == 2 ? "half_width" : "contact_radius",
               number(dim == 2 ? run.contact.half_width : run.contact.contact_radius)},
              {"max_pressure", number(run.contact.max_pressure)},
              {"total_force", number(run.contact.total_force)},
              {"timings", timings}};
  // With friction: the tangential residual, and Coulomb's fixed point (its Tresca solves, last change).
  if (run.result.lambda_t.size() > 0) {
    out["tangential_residual"] = number(c.tangential);
    for (const char* key : {"fixed_point_steps", "fixed_point_change"}) {
      const auto it = run.result.diagnostics.find(key);
      if (it != run.result.diagnostics.end()) out[key] = number(it->second);
    }
  }
  return out;
}

}  // namespace

std::string compare_json(const CompareReport& report) {
  json out;
  out["scene"] = report.model->scene.source;
  out["tol"] = number(report.tol);
  out["dofs"] = report.qp->n_dofs();
  out["constraints"] = report.qp->n_constraints();
  out["reference"] = report.reference >= 0 ? json(to_string(report.runs[report.reference].backend)) : json(nullptr);
  out["agreement"] = {{"rel_diff_u", number(report.bound.u)},
                      {"rel_diff_lambda", number(report.bound.lambda)},
                      {"relative_duality_gap", number(report.bound.gap)}};
  out["max_pairwise_rel_diff_u"] = number(report.max_diff_u);
  out["max_pairwise_rel_diff_lambda"] = number(report.max_diff_lambda);
  out["agree"] = report.agree;
  out["factorize_seconds"] = number(report.factorize_seconds);
  out["linear_solve_seconds"] = number(report.linear_solve_seconds);
  json list = json::array();
  for (const BackendRun& run : report.runs)
    list.push_back(run_json(run, report.linear_solve_seconds, report.model->dim));
  out["runs"] = list;
  out["timings"] = {{"mesh", number(report.timings.get("mesh"))},
                    {"assemble", number(report.timings.get("assemble"))},
                    {"total", number(report.timings.get("total"))}};
  return out.dump(2) + "\n";
}

}  // namespace contactqp
