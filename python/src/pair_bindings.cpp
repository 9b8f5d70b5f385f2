// SceneResult.pairs and SceneResult.bodies: a scene with several bodies (docs/bodies.md) seen
// from Python, with the numbers of the result JSON's "pairs" and "bodies" (result_json.cpp).
// Each view holds the report it came from, so it stays valid after the SceneResult is gone.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "convert.hpp"

namespace contactqp::python {
namespace {

struct PairView {
  std::shared_ptr<const RunReport> report;
  int index;
  const PairContact& pair() const { return report->pairs[index]; }
  int dim() const { return report->model->dim; }
};

struct BodyView {
  std::shared_ptr<const RunReport> report;
  int index;
  const ModelBody& body() const { return report->model->bodies[index]; }
};

// The first dim components, as the JSON writes vectors.
Eigen::VectorXd head(const Eigen::Vector3d& v, int dim) { return v.head(dim); }

// The profile's nodal forces and node numbers, in the same order as its rows.
Eigen::VectorXd profile_forces(const std::vector<ContactProfilePoint>& profile) {
  Eigen::VectorXd out(profile.size());
  for (size_t i = 0; i < profile.size(); ++i) out[i] = profile[i].force;
  return out;
}
Eigen::VectorXi profile_nodes(const std::vector<ContactProfilePoint>& profile) {
  Eigen::VectorXi out(profile.size());
  for (size_t i = 0; i < profile.size(); ++i) out[i] = profile[i].node;
  return out;
}

// The contact force of every pair on body b, summed (the JSON's bodies[b].contact_force).
Eigen::Vector3d body_contact_force(const RunReport& report, int b) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const PairContact& pair : report.pairs) {
    if (pair.node_body == b) force += pair.force_on_node_body;
    if (pair.face_body == b) force += pair.force_on_face_body;
  }
  return force;
}

}  // namespace

py::list pairs_list(const std::shared_ptr<const RunReport>& report) {
  py::list list;
  for (int i = 0; i < static_cast<int>(report->pairs.size()); ++i) list.append(PairView{report, i});
  return list;
}

py::list bodies_list(const std::shared_ptr<const RunReport>& report) {
  py::list list;
  for (int i = 0; i < static_cast<int>(report->model->bodies.size()); ++i) list.append(BodyView{report, i});
  return list;
}

void bind_pairs(py::module_& m) {
  py::class_<PairView>(m, "PairResult", R"(The contact of one pair of bodies (docs/bodies.md), read-only.

Forces are for the whole bodies (doubled by a 2D symmetry plane, four times a 3D quarter
model's), for the thickness in 2D; the same numbers as the result JSON's pairs[i].)")
      .def_property_readonly(
          "pair", [](const PairView& v) { return v.pair().pair; }, "index into the scene's contact pairs")
      .def_property_readonly(
          "node_side", [](const PairView& v) { return v.pair().node_side; },
          "'body.boundary' whose nodes carry the rows")
      .def_property_readonly(
          "face_side", [](const PairView& v) { return v.pair().face_side; }, "'body.boundary' whose faces they meet")
      .def_property_readonly(
          "node_body", [](const PairView& v) { return v.pair().node_body; },
          "index of the node side's body in SceneResult.bodies")
      .def_property_readonly(
          "face_body", [](const PairView& v) { return v.pair().face_body; },
          "index of the face side's body in SceneResult.bodies")
      .def_property_readonly(
          "side_rule", [](const PairView& v) { return v.pair().side_rule; }, "why the nodes are on that side")
      .def_property_readonly(
          "rows", [](const PairView& v) { return v.pair().rows; },
          "\"node_to_face\" or \"mortar\": how the pair's rows tie the two sides (contact.rows)")
      .def_property_readonly(
          "force_on_node_body", [](const PairView& v) { return head(v.pair().force_on_node_body, v.dim()); },
          "the face side's push on the node side's body: sum lam_i n_i (global axes, dim entries)")
      .def_property_readonly(
          "force_on_face_body", [](const PairView& v) { return head(v.pair().force_on_face_body, v.dim()); },
          "the reaction on the face side's body: -sum_i lam_i sum_j N_j n_i")
      .def_property_readonly(
          "action_reaction_residual", [](const PairView& v) { return v.pair().action_reaction; },
          "|F_node + F_face| / max(|F_node|, |F_face|): 0 up to round-off")
      .def_property_readonly(
          "total_force", [](const PairView& v) { return v.pair().total_force; }, "sum of lam_i (whole bodies)")
      .def_property_readonly(
          "line_load", [](const PairView& v) { return v.pair().line_load; },
          "2D: |F_node| / thickness, Hertz's P; 3D: |F_node|")
      .def_property_readonly(
          "normal", [](const PairView& v) { return head(v.pair().normal, v.dim()); },
          "the mean contact normal, into the node side")
      .def_property_readonly(
          "half_width", [](const PairView& v) { return v.pair().half_width; },
          "2D: b = 2 sqrt(sum lam (s - s_mean)^2 / sum lam) along the tangent of the mean normal")
      .def_property_readonly(
          "half_width_last_node", [](const PairView& v) { return v.pair().half_width_last_node; },
          "2D: |s - s_mean| of the farthest node carrying force")
      .def_property_readonly(
          "centre", [](const PairView& v) { return v.pair().centre; }, "2D: s_mean (0 with symmetry)")
      .def_property_readonly(
          "contact_radius", [](const PairView& v) { return v.pair().contact_radius; },
          "3D: a = sqrt(5/2 sum lam r^2 / sum lam)")
      .def_property_readonly(
          "contact_radius_last_node", [](const PairView& v) { return v.pair().contact_radius_last_node; },
          "3D: r of the farthest node carrying force")
      .def_property_readonly(
          "contact_area", [](const PairView& v) { return v.pair().contact_area; },
          "3D: the loaded area (whole bodies); 0 in 2D")
      .def_property_readonly(
          "max_pressure", [](const PairView& v) { return v.pair().max_pressure; },
          "node side's peak pressure (2D: the largest three-node patch average; docs/bodies.md)")
      .def_property_readonly(
          "max_nodal_pressure", [](const PairView& v) { return v.pair().max_nodal_pressure; },
          "node side's max lam_i / w_i, unsmoothed")
      .def_property_readonly(
          "face_max_pressure", [](const PairView& v) { return v.pair().face_max_pressure; },
          "face side's max: sum_i lam_i N_j(xi_i) over node j's tributary")
      .def_property_readonly(
          "contact_nodes", [](const PairView& v) { return v.pair().contact_nodes; },
          "node side's nodes carrying force (lam_i > 1e-8 max lam)")
      .def_property_readonly(
          "slipped_nodes", [](const PairView& v) { return v.pair().slipped_nodes; },
          "loaded nodes whose deformed partner left the faces next to their row's face")
      .def_property_readonly(
          "max_slip", [](const PairView& v) { return v.pair().max_slip; },
          "largest tangential relative displacement of a loaded node")
      .def_property_readonly(
          "profile", [](const PairView& v) { return profile_array(v.pair().profile); },
          "node side: N x 2 array of (s, pressure), sorted by s (3D: s = r from the centre)")
      .def_property_readonly(
          "profile_force", [](const PairView& v) { return profile_forces(v.pair().profile); },
          "node side: lam_i, in the order of profile's rows")
      .def_property_readonly(
          "profile_node", [](const PairView& v) { return profile_nodes(v.pair().profile); },
          "node side: the node of each of profile's rows (global numbering)")
      .def_property_readonly(
          "face_profile", [](const PairView& v) { return profile_array(v.pair().face_profile); },
          "face side: M x 2 array of (s, pressure) of its nodes, sorted by s")
      .def_property_readonly(
          "face_profile_force", [](const PairView& v) { return profile_forces(v.pair().face_profile); },
          "face side: each node's share sum_i lam_i N_j(xi_i), in face_profile's order")
      .def_property_readonly(
          "face_profile_node", [](const PairView& v) { return profile_nodes(v.pair().face_profile); },
          "face side: the node of each of face_profile's rows")
      .def_property_readonly(
          "hertz", [](const PairView& v) { return v.pair().hertz ? py::cast(*v.pair().hertz) : py::none(); },
          "two cylinders (2D) or spheres (3D): a contactqp.HertzComparison, or None")
      .def("__repr__", [](const PairView& v) {
        return "<contactqp.PairResult " + v.pair().node_side + " / " + v.pair().face_side +
               " force=" + format_value(v.pair().line_load) + ">";
      });

  py::class_<BodyView>(m, "BodyResult", R"(One body of a scene with several (docs/bodies.md), read-only.

Its nodes are node numbers first_node .. first_node + nodes - 1 of the joined mesh (so its
displacement is SceneResult.displacement[dim*first_node : dim*(first_node + nodes)]); the same
numbers as the result JSON's bodies[i].)")
      .def_property_readonly(
          "name", [](const BodyView& v) { return v.body().name; }, "the scene's bodies[i].name")
      .def_property_readonly(
          "shape", [](const BodyView& v) { return v.body().scene.body.shape; }, "e.g. 'half_disc'")
      .def_property_readonly(
          "E", [](const BodyView& v) { return v.body().scene.material.E; }, "Young's modulus")
      .def_property_readonly(
          "nu", [](const BodyView& v) { return v.body().scene.material.nu; }, "Poisson's ratio")
      .def_property_readonly(
          "radius", [](const BodyView& v) { return v.body().scene.body.radius; }, "the shape's radius (0 if none)")
      .def_property_readonly(
          "nodes", [](const BodyView& v) { return v.body().n_nodes; }, "its number of nodes")
      .def_property_readonly(
          "elements", [](const BodyView& v) { return v.body().n_elements; }, "its number of elements")
      .def_property_readonly(
          "first_node", [](const BodyView& v) { return v.body().first_node; }, "its first node in the joined mesh")
      .def_property_readonly(
          "first_element", [](const BodyView& v) { return v.body().first_element; },
          "its first element in the joined mesh")
      .def_property_readonly(
          "contact_force",
          [](const BodyView& v) { return head(body_contact_force(*v.report, v.index), v.report->model->dim); },
          "the contact force of every pair on this body, summed (global axes, whole body)")
      .def("__repr__", [](const BodyView& v) {
        return "<contactqp.BodyResult " + v.body().name + " nodes=" + std::to_string(v.body().n_nodes) + ">";
      });
}

}  // namespace contactqp::python
