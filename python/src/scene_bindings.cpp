// contactqp.solve_scene() and compare_scene(): the command line's `solve` and `compare` as
// calls (run.hpp), their reports as Python objects holding the same numbers as the JSON.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "convert.hpp"

namespace contactqp::python {
namespace {

// A contact summary with the model it belongs to (for the candidate rule and Hertz).
struct ContactView {
  std::shared_ptr<const Model> model;
  ContactSummary summary;
};

py::object hertz_object(const std::optional<HertzComparison>& hertz) { return hertz ? py::cast(*hertz) : py::none(); }

py::list obstacles_list(const ContactView& view) {
  py::list list;
  for (const ObstacleContact& o : view.summary.obstacles) {
    py::dict entry;
    entry["obstacle"] = o.obstacle;
    entry["type"] = view.model->scene.obstacles[o.obstacle].type();
    entry["total_force"] = o.total_force;
    entry["line_load"] = o.line_load;
    const int dim = view.model->dim;
    entry["resultant"] = py::cast(Eigen::VectorXd(o.resultant.head(dim)));
    if (dim == 2) {
      entry["half_width"] = o.half_width;
      entry["half_width_last_node"] = o.half_width_last_node;
      entry["centre"] = o.centre;
    } else {
      entry["contact_radius"] = o.contact_radius;
      entry["contact_radius_last_node"] = o.contact_radius_last_node;
      entry["contact_area"] = o.contact_area;
      entry["centre"] = py::cast(Eigen::VectorXd(o.centre_point));
    }
    entry["max_pressure"] = o.max_pressure;
    entry["contact_nodes"] = o.contact_nodes;
    entry["profile"] = profile_array(o.profile);
    entry["hertz"] = hertz_object(compare_with_hertz(*view.model, o));
    list.append(entry);
  }
  return list;
}

py::list reactions_list(const std::vector<Reaction>& reactions, int dim) {
  py::list list;
  for (const Reaction& r : reactions) {
    py::dict entry;
    entry["load"] = r.load;
    entry["boundary"] = r.boundary;
    entry["force"] = py::cast(Eigen::VectorXd(r.force.head(dim)));
    if (r.rigid_surface()) {  // a force load: how far its rigid surface moved (None: free)
      py::list moved;
      for (int c = 0; c < dim; ++c)
        moved.append(r.displacement[c] ? py::object(py::float_(*r.displacement[c])) : py::none());
      entry["displacement"] = moved;
    }
    if (r.turns()) {  // a moment: what it carries and how far it turned (2D: about z; None: held)
      py::list moment, turned;
      for (int a = 0; a < 3; ++a) {
        moment.append(r.rotation[a] ? py::object(py::float_(r.moment[a])) : py::none());
        turned.append(r.rotation[a] ? py::object(py::float_(*r.rotation[a])) : py::none());
      }
      entry["moment"] = dim == 2 ? moment[2] : py::object(moment);
      entry["rotation"] = dim == 2 ? turned[2] : py::object(turned);
      entry["about"] = py::cast(Eigen::VectorXd(r.about.head(dim)));
    }
    list.append(entry);
  }
  return list;
}

std::string scene_path(py::handle path) {
  try {
    return py::str(py::module_::import("os").attr("fspath")(path));
  } catch (py::error_already_set&) {
    throw InputError("path", "is a " + std::string(py::str(py::type::of(path).attr("__name__"))) + ": must be a path");
  }
}

RunReport run(py::handle path, const SolverArguments& arguments, py::object observer, bool no_contact,
              py::object max_elements) {
  Scene scene = load_scene(scene_path(path));
  apply(arguments, scene.solver);
  RunOptions options;
  options.no_contact = no_contact;
  if (!max_elements.is_none()) options.build.max_elements = to_positive_integer(max_elements, "max_elements");
  Observer watch(observer, "observer");
  watch.install(scene.solver);
  RunReport report;
  {
    py::gil_scoped_release release;
    report = run_scene(scene, options);
  }
  watch.rethrow_if_failed();
  report.result.K_factor.reset();  // memory, not data: the certificate is already computed
  return report;
}

std::vector<Backend> backend_list(py::handle backends) {
  std::vector<Backend> list;
  if (backends.is_none()) return list;
  if (py::isinstance<py::str>(backends) || !py::isinstance<py::iterable>(backends))
    throw InputError("backends", "must be a list of contactqp.Backend values or names");
  for (py::handle b : backends) {
    const Backend backend = to_backend(b, "backends");
    for (Backend seen : list)
      if (seen == backend) throw InputError("backends", "lists \"" + to_string(backend) + "\" twice");
    list.push_back(backend);
  }
  if (list.empty())
    throw InputError("backends", "is empty: name at least one backend, or None for every available one");
  return list;
}

const char* const kSolveSceneDoc =
    R"(Run a scene file as `contactqp solve` does: mesh, QP, solve, certificate, post-processing.

Arguments other than path override the scene's "solver" section when not None: backend,
tol, rho, max_iterations, verbose, backend_options, scale (see help(contactqp.solve)), and
  observer      callable observer(k, u, lam) for each iterate
  no_contact    drop the contact rows: one linear solve of the same K [False]
  max_elements  refuse meshes with more elements [4000000]

Returns a contactqp.SceneResult whose attributes hold the numbers of the CLI's --json file
(status, iterations, u, lam, certificate, timings, contact, hertz, reactions, ...); its
json(), csv() and vtu() methods give the files themselves.

Example:
  >>> r = contactqp.solve_scene("scenes/hertz.json", backend=contactqp.Backend.ACTIVE_SET, tol=1e-8)
  >>> r.contact.total_force, r.hertz.half_width, r.hertz.error_max_pressure
)";

const char* const kCompareSceneDoc =
    R"(Solve a scene with several backends and cross-check them, as `contactqp compare` does.

  backends   a list of contactqp.Backend values or names [every available backend]
  tol, rho, max_iterations, backend_options, scale, max_elements: as for solve_scene()

Returns a contactqp.Comparison: runs (one per backend, each with u, lam, certificate, contact,
rel_diff_u, rel_diff_lambda), reference, agree, max_diff_u, max_diff_lambda, max_gap, bound,
factorize_seconds, linear_solve_seconds; json() gives the CLI's --json file.

Example:
  >>> c = contactqp.compare_scene("scenes/hertz.json", tol=1e-10)
  >>> c.agree, [(r.backend.label, r.iterations) for r in c.runs]
)";

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<HertzComparison>(m, "HertzComparison",
                              "Hertz's solution for the computed force, and the errors against it.")
      .def_readonly("dim", &HertzComparison::dim, "2: two cylinders (b, per length); 3: two spheres (a)")
      .def_readonly("radius", &HertzComparison::radius, "radius of relative curvature R")
      .def_readonly("force", &HertzComparison::force, "P: per length in 2D, the whole force in 3D")
      .def_readonly("contact_radius", &HertzComparison::contact_radius, "3D: a = (3 P R / (4 E*))^(1/3)")
      .def_readonly("error_contact_radius", &HertzComparison::error_contact_radius, "3D: (a_computed - a) / a")
      .def_readonly("radius_source", &HertzComparison::radius_source, "where R came from, e.g. 'body.radius'")
      .def_readonly("effective_modulus", &HertzComparison::effective_modulus, "E* = E/(1 - nu^2) in plane strain")
      .def_readonly("half_width", &HertzComparison::half_width, "b = sqrt(4 P R / (pi E*))")
      .def_readonly("max_pressure", &HertzComparison::max_pressure, "p0 = 2 P / (pi b)")
      .def_readonly("error_half_width", &HertzComparison::error_half_width, "(b_computed - b) / b")
      .def_readonly("error_max_pressure", &HertzComparison::error_max_pressure, "(p_max - p0) / p0")
      .def_readonly("error_l2", &HertzComparison::error_l2, "||p_h - p_Hertz||_L2 / ||p_Hertz||_L2")
      .def("__repr__", [](const HertzComparison& h) {
        return "<contactqp.HertzComparison b=" + format_value(h.half_width) + " p0=" + format_value(h.max_pressure) +
               ">";
      });

  py::class_<PunchComparison>(m, "PunchComparison",
                              "Boussinesq's flat punch: P = 2 a E* delta, and the errors against it (3D).")
      .def_readonly("radius", &PunchComparison::radius, "the punch radius a")
      .def_readonly("approach", &PunchComparison::approach, "delta, the prescribed approach")
      .def_readonly("effective_modulus", &PunchComparison::effective_modulus, "E* = E/(1 - nu^2)")
      .def_readonly("force", &PunchComparison::force, "Boussinesq's P = 2 a E* delta")
      .def_readonly("error_force", &PunchComparison::error_force, "(P_computed - P) / P")
      .def_readonly("shape_error", &PunchComparison::shape_error,
                    "max |p(r) 2 pi a sqrt(a^2 - r^2) / P - 1| for r <= 0.8 a");

  py::class_<ContactView>(m, "ContactResult", "The contact of a solved scene: force, half-width, pressure, profile.")
      .def_property_readonly(
          "total_force", [](const ContactView& v) { return v.summary.total_force; },
          "sum of nodal contact forces (doubled with symmetry)")
      .def_property_readonly(
          "line_load", [](const ContactView& v) { return v.summary.line_load; }, "total_force / thickness")
      .def_property_readonly(
          "half_width", [](const ContactView& v) { return v.summary.half_width; },
          "2 sqrt(sum lam (s - s_mean)^2 / sum lam)")
      .def_property_readonly("half_width_last_node",
                             [](const ContactView& v) { return v.summary.half_width_last_node; })
      .def_property_readonly(
          "contact_radius", [](const ContactView& v) { return v.summary.contact_radius; },
          "3D: sqrt(5/2 sum lam r^2 / sum lam), exact for a Hertz pressure")
      .def_property_readonly("contact_radius_last_node",
                             [](const ContactView& v) { return v.summary.contact_radius_last_node; })
      .def_property_readonly(
          "contact_area", [](const ContactView& v) { return v.summary.contact_area; }, "3D: the loaded area")
      .def_property_readonly("max_pressure", [](const ContactView& v) { return v.summary.max_pressure; })
      .def_property_readonly("contact_nodes", [](const ContactView& v) { return v.summary.contact_nodes; })
      .def_property_readonly("candidate_max_gap", [](const ContactView& v) { return v.model->max_gap; })
      .def_property_readonly("candidate_rule", [](const ContactView& v) { return v.model->max_gap_rule; })
      .def_property_readonly("penetrating_non_candidates",
                             [](const ContactView& v) { return v.summary.penetrating_non_candidates; })
      .def_property_readonly(
          "profile", [](const ContactView& v) { return profile_array(v.summary.profile); },
          "N x 2 array of (s, pressure) per candidate, sorted by obstacle then s")
      .def_property_readonly("obstacles", &obstacles_list, "one dict per obstacle, as the JSON's contact.obstacles")
      .def("__repr__", [](const ContactView& v) {
        return "<contactqp.ContactResult force=" + format_value(v.summary.total_force) +
               " half_width=" + format_value(v.summary.half_width) + ">";
      });

  using Report = std::shared_ptr<RunReport>;
  py::class_<RunReport, Report>(m, "SceneResult",
                                R"(The report of contactqp.solve_scene(): the CLI's JSON as attributes.

status, message, backend (None with no_contact), iterations, u (free DOFs), lam, displacement
(every node's, dim per node), certificate, objective, timings, diagnostics, contact, hertz
(None when Hertz does not apply), reactions, floating, pairs and bodies (a scene with several bodies:
contactqp.PairResult, contactqp.BodyResult), dofs, constraints, nodes, elements, element_order,
warnings; json(), csv(), vtu() give the output files' text.)")
      .def_property_readonly("status", [](const RunReport& r) { return r.result.status; })
      .def_property_readonly("converged", [](const RunReport& r) { return r.result.status == Status::Converged; })
      .def_property_readonly("message", [](const RunReport& r) { return r.result.message; })
      .def_property_readonly("backend",
                             [](const RunReport& r) { return r.no_contact ? py::none() : py::cast(r.options.backend); })
      .def_readonly("no_contact", &RunReport::no_contact)
      .def_property_readonly("iterations", [](const RunReport& r) { return r.result.iterations; })
      .def_property_readonly("tol", [](const RunReport& r) { return r.options.tol; })
      .def_property_readonly(
          "u", [](const RunReport& r) { return r.result.u; }, "the QP's solution (free DOFs)")
      .def_property_readonly(
          "lam", [](const RunReport& r) { return r.result.lambda; }, "nodal contact forces, one per candidate")
      .def_property_readonly(
          "displacement", [](const RunReport& r) { return full_displacement(*r.model, r.result.u); },
          "every node's displacement, [u0x, u0y, u1x, ...] in the global frame")
      .def_readonly("certificate", &RunReport::certificate)
      .def_property_readonly("objective", [](const RunReport& r) { return r.certificate.objective; })
      .def_property_readonly(
          "timings", [](const RunReport& r) { return to_dict(r.timings); }, "seconds per phase, 'total' last")
      .def_property_readonly("diagnostics", [](const RunReport& r) { return r.result.diagnostics; })
      .def_property_readonly("contact",
                             [](const RunReport& r) {
                               return ContactView{r.model, r.contact};
                             })
      .def_property_readonly("hertz", [](const RunReport& r) { return hertz_object(r.hertz); })
      .def_property_readonly(
          "boussinesq", [](const RunReport& r) { return r.boussinesq ? py::cast(*r.boussinesq) : py::none(); },
          "Boussinesq's comparison for a scene pressed by a flat punch, else None")
      .def_property_readonly("reactions", [](const RunReport& r) { return reactions_list(r.reactions, r.model->dim); })
      .def_property_readonly(
          "floating",
          [](const RunReport& r) {
            py::list list;
            for (const FloatingBody& body : r.floating) {
              py::list moved;
              for (int c = 0; c < r.model->dim; ++c)
                moved.append(body.translation[c] ? py::object(py::float_(*body.translation[c])) : py::none());
              py::dict entry;
              entry["body"] = body.body;
              entry["translation"] = moved;
              list.append(entry);
            }
            return list;
          },
          "each body only its contacts hold: {'body', 'translation'}, the volume mean of its displacement "
          "along each axis it is free to translate along (None along a held one)")
      .def_property_readonly(
          "pairs", [](const Report& r) { return pairs_list(r); },
          "one contactqp.PairResult per contact pair of a scene with bodies (empty otherwise)")
      .def_property_readonly(
          "bodies", [](const Report& r) { return bodies_list(r); },
          "one contactqp.BodyResult per body of a scene with bodies (empty otherwise)")
      .def_property_readonly(
          "adaptive",
          [](const RunReport& r) -> py::object {
            if (!r.adaptive) return py::none();
            py::list cycles;
            for (const AdaptiveCycle& c : r.adaptive->cycles) {
              py::dict cycle;
              cycle["elements"] = c.elements;
              cycle["dofs"] = c.dofs;
              cycle["energy_norm"] = c.estimate;
              cycle["relative"] = c.relative;
              cycle["strain_energy"] = c.strain_energy;
              cycle["total_force"] = c.total_force;
              cycle["max_pressure"] = c.max_pressure;
              cycle["zone"] = c.zone;
              if (c.friction) {
                cycle["tangential_force"] = c.tangential_force;
                cycle["stick_zone"] = c.stick_zone;
              }
              cycle["iterations"] = c.iterations;
              cycle["seconds"] = c.seconds;
              cycles.append(cycle);
            }
            py::dict out;
            out["target"] = r.adaptive->spec.target;
            out["met"] = r.adaptive->met;
            out["stop"] = r.adaptive->stop;
            out["cycles"] = cycles;
            return out;
          },
          "a scene with \"adapt\" (docs/adaptive.md): {'target', 'met', 'stop', 'cycles': [{'elements', 'dofs', "
          "'energy_norm', 'relative', 'strain_energy', 'total_force', 'max_pressure', 'zone', 'iterations', "
          "'seconds'}]}; "
          "the rest of the result is the last cycle's. None otherwise")
      .def_property_readonly("dofs", [](const RunReport& r) { return r.qp->n_dofs(); })
      .def_property_readonly("constraints", [](const RunReport& r) { return r.qp->n_constraints(); })
      .def_property_readonly("nodes", [](const RunReport& r) { return r.model->mesh.n_nodes(); })
      .def_property_readonly("elements", [](const RunReport& r) { return r.model->mesh.n_elements(); })
      .def_property_readonly("element_order", [](const RunReport& r) { return r.model->mesh.order; })
      .def_readonly("warnings", &RunReport::warnings)
      .def_property_readonly(
          "qp", [](const RunReport& r) { return std::make_shared<QuadraticProgram>(*r.qp); },
          "the assembled QuadraticProgram (a copy), e.g. to solve it again with contactqp.solve()")
      .def(
          "json", [](const RunReport& r) { return result_json(r); },
          "the result JSON, as `contactqp solve --json` writes it")
      .def(
          "csv", [](const RunReport& r) { return profile_csv(r); }, "the pressure profile CSV (--csv)")
      .def(
          "vtu", [](const RunReport& r) { return vtu_document(r); }, "the ParaView .vtu file (--vtu)")
      .def("__repr__", [](const RunReport& r) {
        return "<contactqp.SceneResult " + r.model->scene.source + " status=" + to_string(r.result.status) +
               " iterations=" + std::to_string(r.result.iterations) + " force=" + format_value(r.contact.total_force) +
               ">";
      });

  m.def(
      "solve_scene",
      [](py::object path, py::object backend, py::object tol, py::object rho, py::object max_iterations,
         py::object observer, py::object verbose, py::object backend_options, py::object scale, bool no_contact,
         py::object max_elements) {
        return std::make_shared<RunReport>(run(path,
                                               {backend, tol, rho, max_iterations, verbose, backend_options, scale},
                                               observer, no_contact, max_elements));
      },
      py::arg("path"), py::kw_only(), py::arg("backend") = py::none(), py::arg("tol") = py::none(),
      py::arg("rho") = py::none(), py::arg("max_iterations") = py::none(), py::arg("observer") = py::none(),
      py::arg("verbose") = py::none(), py::arg("backend_options") = py::none(), py::arg("scale") = py::none(),
      py::arg("no_contact") = false, py::arg("max_elements") = py::none(), kSolveSceneDoc);

  struct RunView {
    std::shared_ptr<const CompareReport> report;
    int index;
    const BackendRun& run() const { return report->runs[index]; }
  };
  py::class_<RunView>(m, "BackendRun", "One backend's run in a contactqp.Comparison.")
      .def_property_readonly("backend", [](const RunView& v) { return v.run().backend; })
      .def_property_readonly("status", [](const RunView& v) { return v.run().result.status; })
      .def_property_readonly("converged", [](const RunView& v) { return v.run().result.status == Status::Converged; })
      .def_property_readonly("message", [](const RunView& v) { return v.run().result.message; })
      .def_property_readonly("iterations", [](const RunView& v) { return v.run().result.iterations; })
      .def_property_readonly("seconds", [](const RunView& v) { return v.run().result.timings.get("total"); })
      .def_property_readonly("timings", [](const RunView& v) { return to_dict(v.run().result.timings); })
      .def_property_readonly("diagnostics", [](const RunView& v) { return v.run().result.diagnostics; })
      .def_property_readonly("u", [](const RunView& v) { return v.run().result.u; })
      .def_property_readonly("lam", [](const RunView& v) { return v.run().result.lambda; })
      .def_property_readonly("certificate", [](const RunView& v) { return v.run().certificate; })
      .def_property_readonly("contact",
                             [](const RunView& v) {
                               return ContactView{v.report->model, v.run().contact};
                             })
      .def_property_readonly(
          "rel_diff_u", [](const RunView& v) { return v.run().rel_diff_u; }, "||u - u_ref|| / ||u_ref||, or None")
      .def_property_readonly("rel_diff_lambda", [](const RunView& v) { return v.run().rel_diff_lambda; })
      .def("__repr__", [](const RunView& v) {
        return "<contactqp.BackendRun " + to_string(v.run().backend) + " status=" + to_string(v.run().result.status) +
               ">";
      });

  using Comparison = std::shared_ptr<CompareReport>;
  py::class_<CompareReport, Comparison>(m, "Comparison", "The report of contactqp.compare_scene().")
      .def_property_readonly("runs",
                             [](const Comparison& c) {
                               std::vector<RunView> runs;
                               for (int i = 0; i < static_cast<int>(c->runs.size()); ++i) runs.push_back({c, i});
                               return runs;
                             })
      .def_property_readonly(
          "reference",
          [](const Comparison& c) { return c->reference >= 0 ? py::cast(c->runs[c->reference].backend) : py::none(); },
          "the converged backend with the smallest certified gap, or None")
      .def_property_readonly("agree", [](const Comparison& c) { return c->agree; })
      .def_property_readonly("all_converged", [](const Comparison& c) { return c->all_converged; })
      .def_property_readonly("max_diff_u", [](const Comparison& c) { return c->max_diff_u; })
      .def_property_readonly("max_diff_lambda", [](const Comparison& c) { return c->max_diff_lambda; })
      .def_property_readonly("max_gap", [](const Comparison& c) { return c->max_gap; })
      .def_property_readonly(
          "bound",
          [](const Comparison& c) {
            py::dict d;
            d["u"] = c->bound.u;
            d["lambda"] = c->bound.lambda;
            d["gap"] = c->bound.gap;
            return d;
          },
          "the agreement bounds {u, lambda, gap} at this tol")
      .def_property_readonly("tol", [](const Comparison& c) { return c->tol; })
      .def_property_readonly("dofs", [](const Comparison& c) { return c->qp->n_dofs(); })
      .def_property_readonly("constraints", [](const Comparison& c) { return c->qp->n_constraints(); })
      .def_property_readonly("factorize_seconds", [](const Comparison& c) { return c->factorize_seconds; })
      .def_property_readonly("linear_solve_seconds", [](const Comparison& c) { return c->linear_solve_seconds; })
      .def_property_readonly("timings", [](const Comparison& c) { return to_dict(c->timings); })
      .def_property_readonly("warnings", [](const Comparison& c) { return c->warnings; })
      .def(
          "json", [](const Comparison& c) { return compare_json(*c); }, "the JSON `contactqp compare --json` writes");

  m.def(
      "compare_scene",
      [](py::object path, py::object backends, py::object tol, py::object rho, py::object max_iterations,
         py::object backend_options, py::object scale, py::object max_elements) {
        Scene scene = load_scene(scene_path(path));
        apply({py::none(), tol, rho, max_iterations, py::none(), backend_options, scale}, scene.solver);
        CompareOptions options;
        options.backends = backend_list(backends);
        if (!max_elements.is_none()) options.build.max_elements = to_positive_integer(max_elements, "max_elements");
        py::gil_scoped_release release;
        return std::make_shared<CompareReport>(compare_scene(scene, options));
      },
      py::arg("path"), py::kw_only(), py::arg("backends") = py::none(), py::arg("tol") = py::none(),
      py::arg("rho") = py::none(), py::arg("max_iterations") = py::none(), py::arg("backend_options") = py::none(),
      py::arg("scale") = py::none(), py::arg("max_elements") = py::none(), kCompareSceneDoc);
}

}  // namespace contactqp::python
