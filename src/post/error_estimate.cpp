// The a-posteriori energy-error estimate (estimate.hpp; the derivation is in docs/estimate.md):
// a recovered-stress part over the elements and a contact part over the contact faces.
#include "contactqp/estimate.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>
#include <vector>

#include "contact/contact.hpp"
#include "contactqp/timer.hpp"
#include "estimate_sums.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

template <int dim>
constexpr int kVoigt = dim == 2 ? 3 : 6;
template <int dim>
using Voigt = Eigen::Matrix<double, kVoigt<dim>, 1>;

// Engineering strain from the displacement gradient grad(a, b) = du_a/dx_b: [εxx, εyy, 2εxy]
// in 2D, [εxx, εyy, εzz, 2εyz, 2εxz, 2εxy] in 3D (the order of elasticity_matrix()).
template <int dim>
Voigt<dim> voigt_strain(const Eigen::Matrix<double, dim, dim>& g) {
  Voigt<dim> e;
  if constexpr (dim == 2) {
    e << g(0, 0), g(1, 1), g(0, 1) + g(1, 0);
  } else {
    e << g(0, 0), g(1, 1), g(2, 2), g(1, 2) + g(2, 1), g(0, 2) + g(2, 0), g(0, 1) + g(1, 0);
  }
  return e;
}

// One element's geometry and displacement, and its stress at a reference point: D ε, plus the
// mixed formulation's condensed mean stress p on the normal components (2D).
template <int dim>
struct ElementState {
  Eigen::Matrix<double, dim, Eigen::Dynamic> X, U;
  double pressure = 0;

  // The displacement gradient and |det J| at a point with reference gradients dN.
  Eigen::Matrix<double, dim, dim> gradient(const Eigen::Matrix<double, dim, Eigen::Dynamic>& dN, double& detJ) const {
    const Eigen::Matrix<double, dim, dim> J = dN * X.transpose();  // J(r, c) = dx_c/dξ_r
    detJ = std::abs(J.determinant());
    const Eigen::Matrix<double, dim, Eigen::Dynamic> dNdx = J.inverse() * dN;
    return U * dNdx.transpose();
  }
  Voigt<dim> stress(const Eigen::Matrix<double, kVoigt<dim>, kVoigt<dim>>& D, const Voigt<dim>& strain) const {
    Voigt<dim> s = D * strain;
    if constexpr (dim == 2) {
      s[0] += pressure;
      s[1] += pressure;
    }
    return s;
  }
};

// The reference points the estimate integrates with: the degree-4 rule in 2D (6 points, which
// the stiffness of 6-node triangles uses too) and the degree-2 rule in 3D (4 points, the
// stiffness' of 10-node tetrahedra): exact for ½ σ_h : ε_h on straight elements of both orders,
// so the strain energy is ½ uᵀKu; the recovery part of a 10-node tetrahedron (degree 4) is
// approximate.
template <int dim>
struct EstimateRule {
  std::vector<Eigen::VectorXd> N;
  std::vector<Eigen::Matrix<double, dim, Eigen::Dynamic>> dN;
  std::vector<double> weight;
  std::vector<Eigen::Matrix<double, dim, Eigen::Dynamic>> dN_node;  // at each node, for the nodal stresses
};

template <int dim>
EstimateRule<dim> estimate_rule(int order, int npe) {
  EstimateRule<dim> rule;
  for (const detail::CellPoint<dim>& q : detail::cell_rule<dim>(2)) {
    rule.N.push_back(detail::cell_values<dim>(order, q.xi));
    rule.dN.push_back(detail::cell_gradients<dim>(order, q.xi));
    rule.weight.push_back(q.weight);
  }
  for (int i = 0; i < npe; ++i) rule.dN_node.push_back(detail::cell_gradients<dim>(order, detail::cell_node<dim>(i)));
  return rule;
}

// The elasticity matrix whose inverse measures a stress difference: D, or with the mixed
// formulation D_dev + k m mᵀ (the material's whole D, which the condensed pressure stands for).
template <int dim>
Eigen::Matrix<double, kVoigt<dim>, kVoigt<dim>> full_elasticity(const ElementLaw& law) {
  Eigen::Matrix<double, kVoigt<dim>, kVoigt<dim>> D = law.D;
  if constexpr (dim == 2)
    if (law.bulk > 0) D.template topLeftCorner<2, 2>().array() += law.bulk;
  return D;
}

struct VolumeParts {
  double energy = 0;
  Eigen::VectorXd squared;  // ∫_T (σ* − σ_h) : C⁻¹ : (σ* − σ_h) per element
};

// The strain energy and, with `recovery`, each element's recovery term. Two passes over the
// elements: the nodal stresses (measure-weighted averages of the elements' stresses at the
// node, over every part's elements that hold it: `sum_shared`), then the integral of the
// difference.
template <int dim>
VolumeParts volume_parts(const Model& model, const Eigen::VectorXd& displacement, bool recovery,
                         const detail::SumOverShared& sum_shared) {
  const Mesh& mesh = model.mesh;
  const int npe = mesh.nodes_per_element(), n_elements = mesh.n_elements();
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  const std::vector<ElementLaw> laws = element_laws(model);
  std::vector<Eigen::Matrix<double, kVoigt<dim>, kVoigt<dim>>> D(laws.size()), compliance(laws.size());
  for (size_t b = 0; b < laws.size(); ++b) {
    D[b] = laws[b].D;
    compliance[b] = full_elasticity<dim>(laws[b]).inverse();
  }
  const EstimateRule<dim> rule = estimate_rule<dim>(mesh.order, npe);
  std::vector<Eigen::Vector3d> nodes(npe);
  Eigen::VectorXd ue(dim * npe);
  ElementState<dim> state{Eigen::Matrix<double, dim, Eigen::Dynamic>(dim, npe),
                          Eigen::Matrix<double, dim, Eigen::Dynamic>(dim, npe), 0.0};
  const auto load = [&](int e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      nodes[i] = mesh.nodes[v[i]];
      state.X.col(i) = nodes[i].template head<dim>();
      state.U.col(i) = displacement.template segment<dim>(dim * v[i]);
      ue.template segment<dim>(dim * i) = state.U.col(i);
    }
    state.pressure = 0;
    if constexpr (dim == 2) {
      const ElementLaw& law = laws[body_of_element(model, e)];
      if (law.bulk > 0) state.pressure = law.bulk * element_mean_dilatation(nodes.data(), mesh.order, ue);
    }
    return v;
  };

  VolumeParts parts;
  Eigen::Matrix<double, kVoigt<dim>, Eigen::Dynamic> recovered;
  if (recovery) {
    recovered = Eigen::Matrix<double, kVoigt<dim>, Eigen::Dynamic>::Zero(kVoigt<dim>, mesh.n_nodes());
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.n_nodes());
    for (int e = 0; e < n_elements; ++e) {
      const int* v = load(e);
      const int b = body_of_element(model, e);
      const double measure = std::abs(element_measure(mesh, e));
      double detJ = 0;
      for (int i = 0; i < npe; ++i) {
        const Voigt<dim> strain = voigt_strain<dim>(state.gradient(rule.dN_node[i], detJ));
        recovered.col(v[i]) += measure * state.stress(D[b], strain);
        weight[v[i]] += measure;
      }
    }
    if (sum_shared) {
      sum_shared(recovered.data(), kVoigt<dim>);
      sum_shared(weight.data(), 1);
    }
    for (int k = 0; k < mesh.n_nodes(); ++k)
      if (weight[k] > 0) recovered.col(k) /= weight[k];
    parts.squared = Eigen::VectorXd::Zero(n_elements);
  }
  for (int e = 0; e < n_elements; ++e) {
    const int* v = load(e);
    const int b = body_of_element(model, e);
    double squared = 0;
    for (size_t q = 0; q < rule.weight.size(); ++q) {
      double detJ = 0;
      const Voigt<dim> strain = voigt_strain<dim>(state.gradient(rule.dN[q], detJ));
      const Voigt<dim> stress = state.stress(D[b], strain);
      const double w = rule.weight[q] * detJ * thickness;
      parts.energy += 0.5 * w * stress.dot(strain);
      if (!recovery) continue;
      Voigt<dim> star = Voigt<dim>::Zero();
      for (int i = 0; i < npe; ++i) star += rule.N[q][i] * recovered.col(v[i]);
      const Voigt<dim> difference = star - stress;
      squared += w * difference.dot(compliance[b] * difference);
    }
    if (recovery) parts.squared[e] = squared;
  }
  return parts;
}

// The same for linear elements, whose strain is constant: one gradient per element, and the
// integral of the linear difference d = σ* − σ_h in closed form, ∫_T dᵀ C⁻¹ d =
// |T| / ((dim + 1)(dim + 2)) · (Σ_i d_iᵀ C⁻¹ d_i + (Σ_i d_i)ᵀ C⁻¹ (Σ_i d_i)), d_i at the vertices.
template <int dim>
VolumeParts linear_volume_parts(const Model& model, const Eigen::VectorXd& displacement, bool recovery,
                                const detail::SumOverShared& sum_shared) {
  const Mesh& mesh = model.mesh;
  const int n_elements = mesh.n_elements();
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  const double reference_measure = dim == 2 ? 0.5 : 1.0 / 6.0;
  const std::vector<ElementLaw> laws = element_laws(model);
  std::vector<Eigen::Matrix<double, kVoigt<dim>, kVoigt<dim>>> D(laws.size()), compliance(laws.size());
  for (size_t b = 0; b < laws.size(); ++b) {
    D[b] = laws[b].D;
    compliance[b] = full_elasticity<dim>(laws[b]).inverse();
  }
  const Eigen::Matrix<double, dim, Eigen::Dynamic> dN = detail::cell_gradients<dim>(1, detail::cell_node<dim>(0));
  ElementState<dim> state{Eigen::Matrix<double, dim, Eigen::Dynamic>(dim, dim + 1),
                          Eigen::Matrix<double, dim, Eigen::Dynamic>(dim, dim + 1), 0.0};
  Eigen::Matrix<double, kVoigt<dim>, Eigen::Dynamic> stress(kVoigt<dim>, n_elements);
  Eigen::VectorXd measure(n_elements);
  VolumeParts parts;
  for (int e = 0; e < n_elements; ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i <= dim; ++i) {
      state.X.col(i) = mesh.nodes[v[i]].template head<dim>();
      state.U.col(i) = displacement.template segment<dim>(dim * v[i]);
    }
    double detJ = 0;
    const Voigt<dim> strain = voigt_strain<dim>(state.gradient(dN, detJ));
    stress.col(e) = state.stress(D[body_of_element(model, e)], strain);
    measure[e] = detJ * reference_measure;
    parts.energy += 0.5 * measure[e] * thickness * stress.col(e).dot(strain);
  }
  if (!recovery) return parts;
  Eigen::Matrix<double, kVoigt<dim>, Eigen::Dynamic> recovered =
      Eigen::Matrix<double, kVoigt<dim>, Eigen::Dynamic>::Zero(kVoigt<dim>, mesh.n_nodes());
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.n_nodes());
  for (int e = 0; e < n_elements; ++e)
    for (int i = 0; i <= dim; ++i) {
      recovered.col(mesh.element(e)[i]) += measure[e] * stress.col(e);
      weight[mesh.element(e)[i]] += measure[e];
    }
  if (sum_shared) {
    sum_shared(recovered.data(), kVoigt<dim>);
    sum_shared(weight.data(), 1);
  }
  for (int k = 0; k < mesh.n_nodes(); ++k)
    if (weight[k] > 0) recovered.col(k) /= weight[k];
  parts.squared = Eigen::VectorXd::Zero(n_elements);
  for (int e = 0; e < n_elements; ++e) {
    const auto& C = compliance[body_of_element(model, e)];
    Voigt<dim> sum = Voigt<dim>::Zero();
    double diagonal = 0;
    for (int i = 0; i <= dim; ++i) {
      const Voigt<dim> d = recovered.col(mesh.element(e)[i]) - stress.col(e);
      diagonal += d.dot(C * d);
      sum += d;
    }
    parts.squared[e] = measure[e] * thickness / ((dim + 1) * (dim + 2)) * (diagonal + sum.dot(C * sum));
  }
  return parts;
}

VolumeParts volume_parts(const Model& model, const Eigen::VectorXd& displacement, bool recovery,
                         const detail::SumOverShared& sum_shared = {}) {
  if (model.mesh.order == 1)
    return model.dim == 2 ? linear_volume_parts<2>(model, displacement, recovery, sum_shared)
                          : linear_volume_parts<3>(model, displacement, recovery, sum_shared);
  return model.dim == 2 ? volume_parts<2>(model, displacement, recovery, sum_shared)
                        : volume_parts<3>(model, displacement, recovery, sum_shared);
}

// A face's vertices, sorted: the key that finds it among an element's faces.
using FaceKey = std::array<int, 3>;
FaceKey face_key(const int* nodes, int n_vertices) {
  FaceKey key{{-1, -1, -1}};
  for (int k = 0; k < n_vertices && k < 3; ++k) key[k] = nodes[k];
  // Two or three entries: a sorting network.
  if (key[0] > key[1]) std::swap(key[0], key[1]);
  if (n_vertices == 3) {
    if (key[1] > key[2]) std::swap(key[1], key[2]);
    if (key[0] > key[1]) std::swap(key[0], key[1]);
  }
  return key;
}
struct FaceKeyHash {
  size_t operator()(const FaceKey& k) const {
    return std::hash<long long>()((static_cast<long long>(k[0]) * 1000003 + k[1]) * 1000003 + k[2]);
  }
};

// One point of a face: its shape values (the face's nodes) and the measure it stands for.
struct FacePoint {
  std::array<double, 6> N{};
  double measure = 0;
};

// The points of a face of `n_nodes` nodes at positions x: 3 Gauss points on an edge (2D), the
// 6-point degree-4 rule on a triangle (3D), either straight or quadratic.
std::vector<FacePoint> face_points(const std::vector<Eigen::Vector3d>& x, int dim) {
  std::vector<FacePoint> points;
  const int n = static_cast<int>(x.size());
  if (dim == 2) {
    for (int k = 0; k < 3; ++k) {
      const detail::EdgePoint p = detail::edge_point(detail::kEdgeGaussT[k], x[0], x[1], n == 3 ? &x[2] : nullptr);
      FacePoint point;
      for (int j = 0; j < n; ++j) point.N[j] = p.N[j];
      point.measure = detail::kEdgeGaussW[k] * p.dx.norm();
      points.push_back(point);
    }
    return points;
  }
  const int order = n == 6 ? 2 : 1;
  const detail::QuadraturePoint* rule = nullptr;
  const int n_points = detail::triangle_rule(2, rule);
  for (int k = 0; k < n_points; ++k) {
    const Eigen::VectorXd N = detail::shape_values(order, rule[k].xi, rule[k].eta);
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = detail::shape_gradients(order, rule[k].xi, rule[k].eta);
    Eigen::Vector3d dxi = Eigen::Vector3d::Zero(), deta = Eigen::Vector3d::Zero();
    FacePoint point;
    for (int j = 0; j < n; ++j) {
      point.N[j] = N[j];
      dxi += dN(0, j) * x[j];
      deta += dN(1, j) * x[j];
    }
    point.measure = rule[k].weight * dxi.cross(deta).norm();
    points.push_back(point);
  }
  return points;
}

// E* = E/(1 − ν²) (plane strain, solid) or E (plane stress) of the body a node belongs to.
double effective_modulus(const Model& model, int body) {
  const Material& m = model.bodies.empty() ? model.scene.material : model.bodies[body].scene.material;
  return model.scene.model == ElasticModel::PlaneStress ? m.E : m.E / (1 - m.nu * m.nu);
}

struct ContactParts {
  double squared = 0, friction_squared = 0;
};

// The contact faces' terms, added to their elements' squared indicators. A face counts for an
// obstacle or a pair when each of its nodes has a row of it: the candidates reach beyond the
// zone in contact (contact.max_gap), so the faces where p_h and s_h change hands are among them.
// `pressure` and `slack` per row of model.candidates (estimate_sums.hpp).
ContactParts add_contact_terms(const Model& model, const std::vector<double>& pressure, const Eigen::VectorXd& slack,
                               const FrictionBlock* friction_rows, const Eigen::VectorXd& displacement,
                               const FrictionFields* friction, Eigen::VectorXd& squared) {
  ContactParts parts;
  const int m = static_cast<int>(model.candidates.size());
  if (m == 0 || static_cast<int>(pressure.size()) != m || slack.size() != m) return parts;
  if (!friction_rows) friction = nullptr;
  const Mesh& mesh = model.mesh;
  const int dim = model.dim;
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  // An obstacle's rows by their obstacle (≥ 0), a pair's by −1 − pair.
  const auto target_of = [](const Candidate& c) { return c.pair >= 0 ? -1 - c.pair : c.obstacle; };
  std::unordered_map<int, std::vector<int>> rows_of_node;
  for (int i = 0; i < m; ++i) rows_of_node[model.candidates[i].node].push_back(i);
  const auto row_of = [&](int node, int target) {
    const auto it = rows_of_node.find(node);
    if (it == rows_of_node.end()) return -1;
    for (int i : it->second)
      if (target_of(model.candidates[i]) == target) return i;
    return -1;
  };

  // Each contact face once (a face may be listed under several names), with its rows.
  struct ContactFace {
    BoundaryFace face;
    int target = 0;
    std::vector<int> rows;
  };
  std::vector<ContactFace> faces;
  std::map<std::pair<FaceKey, int>, bool> seen;
  for (const auto& [name, list] : mesh.boundaries)
    for (const BoundaryFace& face : list) {
      if (face.n_nodes == 0) continue;
      const auto first = rows_of_node.find(face.node(0));
      if (first == rows_of_node.end()) continue;
      for (int i0 : first->second) {
        const int target = target_of(model.candidates[i0]);
        std::vector<int> rows;
        for (int k = 0; k < face.n_nodes; ++k) {
          const int i = row_of(face.node(k), target);
          if (i < 0) break;
          rows.push_back(i);
        }
        if (static_cast<int>(rows.size()) != face.n_nodes) continue;
        if (!seen.emplace(std::make_pair(face_key(face.nodes.data(), dim), target), true).second) continue;
        faces.push_back({face, target, rows});
      }
    }
  if (faces.empty()) return parts;

  // The element each face belongs to.
  std::unordered_map<FaceKey, int, FaceKeyHash> owner;
  std::vector<char> on_face(mesh.n_nodes(), 0);  // only elements with a vertex on a contact face can own one
  for (const ContactFace& f : faces) {
    owner.emplace(face_key(f.face.nodes.data(), dim), -1);
    for (int k = 0; k < dim; ++k) on_face[f.face.node(k)] = 1;
  }
  const std::vector<std::vector<int>>& local_faces = element_faces(mesh.type());
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    if (!on_face[v[0]] && !on_face[v[1]] && !on_face[v[2]] && (dim == 2 || !on_face[v[3]])) continue;
    for (const std::vector<int>& local : local_faces) {
      int vertices[3];
      for (int k = 0; k < dim; ++k) vertices[k] = v[local[k]];
      const auto it = owner.find(face_key(vertices, dim));
      if (it != owner.end()) it->second = e;
    }
  }

  for (const ContactFace& f : faces) {
    const int n = f.face.n_nodes;
    std::vector<Eigen::Vector3d> x(n), w(n, Eigen::Vector3d::Zero()), q(n, Eigen::Vector3d::Zero());
    std::vector<double> p(n), s(n), bound(n, 0.0);
    double size = 0;
    for (int k = 0; k < n; ++k) {
      const int i = f.rows[k];
      x[k] = mesh.nodes[f.face.node(k)];
      p[k] = pressure[i];
      s[k] = slack[i];
      if (friction) {
        w[k] = friction->slip[i];
        q[k] = friction->traction[i];
        // The bound's density: Coulomb's μ p; Tresca's threshold over the tributary, or the
        // traction itself where the tributary is 0 (a vertex of a 6-node face in 3D).
        const double tributary = model.candidates[i].tributary * thickness;
        if (friction_rows->law == FrictionLaw::Coulomb)
          bound[k] = friction_rows->coefficient[i] * p[k];
        else
          bound[k] = tributary > 0 ? friction->bound[i] / tributary : q[k].norm();
        bound[k] = std::max(bound[k], q[k].norm());
      }
    }
    for (int a = 0; a < dim; ++a)
      for (int b = a + 1; b < dim; ++b) size = std::max(size, (x[a] - x[b]).norm());
    const Candidate& row = model.candidates[f.rows[0]];
    const double modulus = effective_modulus(model, row.body);
    double complementarity = 0, penetration = 0, dissipation = 0;
    for (const FacePoint& point : face_points(x, dim)) {
      double ph = 0, sh = 0, bh = 0;
      Eigen::Vector3d position = Eigen::Vector3d::Zero(), wh = Eigen::Vector3d::Zero(), qh = Eigen::Vector3d::Zero();
      for (int k = 0; k < n; ++k) {
        ph += point.N[k] * p[k];
        sh += point.N[k] * s[k];
        bh += point.N[k] * bound[k];
        wh += point.N[k] * w[k];
        qh += point.N[k] * q[k];
        position += point.N[k] * x[k];
        position.head(dim) += point.N[k] * displacement.segment(dim * f.face.node(k), dim);
      }
      // On an obstacle the deformed gap itself, which a curved obstacle makes negative between
      // nodes whose rows hold; a pair's rows are linearised, and their slack is interpolated.
      if (f.target >= 0) sh = detail::project(model.scene.obstacles[f.target], position).gap;
      const double ds = point.measure * thickness;
      // |p_h|: quadratic shape functions dip below 0, and so may p_h between nonnegative nodal values.
      complementarity += ds * std::abs(ph) * std::abs(sh);
      penetration += ds * std::min(sh, 0.0) * std::min(sh, 0.0);
      if (friction) dissipation += ds * std::max(0.0, bh * wh.norm() + qh.dot(wh));
    }
    const double term = 2 * complementarity + (size > 0 ? modulus / size : 0.0) * penetration + 2 * dissipation;
    parts.squared += term;
    parts.friction_squared += 2 * dissipation;
    const int e = owner.at(face_key(f.face.nodes.data(), dim));
    if (e >= 0) squared[e] += term;
  }
  return parts;
}

}  // namespace

namespace detail {

EstimateSums estimate_sums(const Model& model, const Eigen::VectorXd& displacement, const std::vector<double>& pressure,
                           const Eigen::VectorXd& slack, const FrictionBlock* friction_rows,
                           const FrictionFields* friction, const SumOverShared& sum_shared) {
  VolumeParts volume = volume_parts(model, displacement, true, sum_shared);
  EstimateSums sums;
  sums.energy = volume.energy;
  sums.recovery = volume.squared.sum();
  const ContactParts contact =
      add_contact_terms(model, pressure, slack, friction_rows, displacement, friction, volume.squared);
  sums.contact = contact.squared;
  sums.friction = contact.friction_squared;
  sums.total = volume.squared.sum();
  sums.squared = std::move(volume.squared);
  return sums;
}

ErrorEstimate estimate_from_sums(const EstimateSums& sums, const Eigen::VectorXd& indicator_squared,
                                 bool force_estimate) {
  ErrorEstimate estimate;
  estimate.strain_energy = sums.energy;
  estimate.recovery = std::sqrt(sums.recovery);
  estimate.contact = std::sqrt(sums.contact);
  estimate.friction = std::sqrt(sums.friction);
  estimate.estimate = std::sqrt(sums.total);
  const double norm = std::sqrt(2 * std::max(estimate.strain_energy, 0.0));
  estimate.relative = norm > 0 ? estimate.estimate / norm : 0.0;
  // The force conjugate to a prescribed push δ is P = dE/dδ; where E and E_h are both
  // homogeneous of one degree k in δ (linear elasticity with the contact zone growing with δ, as
  // Hertz's), P_h − P = k (E_h − E)/δ and (P_h − P)/P = (E_h − E)/E ≈ ½ η² / E = relative².
  // Force loads and friction (whose dissipation is no energy) break the argument, and so do
  // quadratic elements: their faces penetrate between nodes and their force error is not the
  // energy's (measured: a fifth of it on Hertz's cylinder, and of either sign; docs/estimate.md).
  if (force_estimate) estimate.force_relative = estimate.relative * estimate.relative;
  estimate.indicator = indicator_squared.cwiseSqrt();
  estimate.max_indicator = estimate.indicator.size() ? estimate.indicator.maxCoeff() : 0.0;
  return estimate;
}

}  // namespace detail

ErrorEstimate estimate_error(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& lambda, const FrictionFields* friction) {
  Stopwatch clock;
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const bool rows = qp.n_constraints() > 0 && lambda.size() == qp.n_constraints() &&
                    static_cast<int>(model.candidates.size()) == qp.n_constraints();
  const std::vector<double> pressure = rows ? nodal_pressures(model, qp, lambda) : std::vector<double>();
  const Eigen::VectorXd slack = rows ? Eigen::VectorXd(qp.g - qp.B * u) : Eigen::VectorXd();
  const detail::EstimateSums sums = detail::estimate_sums(model, displacement, pressure, slack,
                                                          qp.friction.empty() ? nullptr : &qp.friction, friction);
  const bool pushed = model.prescribed.size() && model.prescribed.cwiseAbs().maxCoeff() > 0;
  const bool forced = model.nodal_force.size() && model.nodal_force.cwiseAbs().maxCoeff() > 0;
  const bool force_estimate = pushed && !forced && model.mesh.order == 1 && qp.friction.empty() && rows;
  ErrorEstimate estimate = detail::estimate_from_sums(sums, sums.squared, force_estimate);
  estimate.seconds = clock.seconds();
  return estimate;
}

double strain_energy(const Model& model, const Eigen::VectorXd& u) {
  return volume_parts(model, full_displacement(model, u), false).energy;
}

}  // namespace contactqp
