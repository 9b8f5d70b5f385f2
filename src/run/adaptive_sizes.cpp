#include "adaptive_sizes.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "mesh/point_locator.hpp"

namespace contactqp::detail {
namespace {

// Per cycle, no element shrinks below a quarter or grows beyond twice its size: the error
// model holds only roughly, and the next cycle corrects what this one got wrong.
constexpr double kMinRatio = 0.25, kMaxRatio = 2.0;

// The size Gmsh is asked for that gives an element of this measure: the edge of the regular
// simplex of that area (2D) or volume (3D). Gmsh's tetrahedra come out larger than the size
// asked for, 1/0.6 of the regular volume on the generated shapes (graded_size.cpp), which the
// 3D factor takes into account.
double size_of_measure(double measure, int dim) {
  return dim == 2 ? std::sqrt(measure * 4 / std::sqrt(3.0)) : std::cbrt(measure * 6 * std::sqrt(2.0) * 0.6);
}

double simplex_measure(const Mesh& mesh, int e) {
  const int* v = mesh.element(e);
  Eigen::Matrix3d edges = Eigen::Matrix3d::Identity();
  for (int k = 0; k < mesh.dim; ++k) edges.col(k) = mesh.nodes[v[k + 1]] - mesh.nodes[v[0]];
  return std::abs(edges.determinant()) / (mesh.dim == 2 ? 2 : 6);
}

}  // namespace

NextMesh plan_next_mesh(const Model& model, const Eigen::VectorXd& indicator, double wanted_estimate,
                        const NextMeshLimits& limits) {
  const Mesh& mesh = model.mesh;
  const int dim = mesh.dim, n_elements = mesh.n_elements();
  if (indicator.size() != n_elements) throw std::invalid_argument("plan_next_mesh: one indicator per element");
  const int n_bodies = std::max<int>(1, static_cast<int>(model.bodies.size()));
  if (static_cast<int>(limits.max_size.size()) != n_bodies)
    throw std::invalid_argument("plan_next_mesh: one max_size per body");
  const double exponent = 2.0 / (2 * mesh.order + dim);  // r = (e / η_T)^exponent

  std::vector<double> size(n_elements), upper(n_elements);
  double fixed_elements = 0, fixed_error = 0, largest = 0;
  for (int e = 0; e < n_elements; ++e) {
    size[e] = size_of_measure(simplex_measure(mesh, e), dim);
    const double max_size = limits.max_size[body_of_element(model, e)];
    upper[e] = max_size > 0 ? std::clamp(max_size / size[e], kMinRatio, kMaxRatio) : 0;
    if (upper[e] == 0) {  // a body that keeps its mesh
      fixed_elements += 1;
      fixed_error += indicator[e] * indicator[e];
    }
    largest = std::max(largest, indicator[e]);
  }
  const auto ratio = [&](int e, double share) {
    if (upper[e] == 0) return 1.0;
    if (!(indicator[e] > 0)) return upper[e];
    return std::clamp(std::pow(share / indicator[e], exponent), kMinRatio, upper[e]);
  };
  const auto expected = [&](double share) {  // (elements, η²) of the next mesh
    double elements = fixed_elements, error = fixed_error;
    for (int e = 0; e < n_elements; ++e) {
      if (upper[e] == 0) continue;
      const double r = ratio(e, share);
      elements += std::pow(r, -dim);
      error += indicator[e] * indicator[e] * std::pow(r, 2 * mesh.order);
    }
    return std::pair{elements, error};
  };
  // The expected η grows with e and the expected elements fall, so the share wanted is the larger
  // of the largest e that meets the target and the smallest e within the growth allowed: the
  // end of the range where "met, or too many elements" holds, found by bisection in log(e).
  const double max_elements = limits.max_growth * n_elements;
  double low = std::log(std::max(largest, 1e-300)) - 60, high = std::log(std::max(largest, 1e-300)) + 1;
  for (int k = 0; k < 200 && high - low > 1e-10; ++k) {
    const double middle = 0.5 * (low + high);
    const auto [elements, error] = expected(std::exp(middle));
    (std::sqrt(error) <= wanted_estimate || elements > max_elements ? low : high) = middle;
  }
  const double share = std::exp(low);
  const auto [elements, error] = expected(share);

  NextMesh next;
  next.elements = elements;
  next.estimate = std::sqrt(error);
  next.size_fields.resize(n_bodies);
  for (int b = 0; b < n_bodies; ++b) {
    if (limits.max_size[b] <= 0) continue;
    const bool several = !model.bodies.empty();
    const int first = several ? model.bodies[b].first_element : 0;
    const int count = several ? model.bodies[b].n_elements : n_elements;
    // The body's vertices, renumbered, in its own frame; each the geometric mean of its elements' sizes.
    std::vector<int> vertex_of(mesh.n_nodes(), -1);
    std::vector<Eigen::Vector3d> vertices;
    std::vector<double> log_sum, weight;
    std::vector<std::array<int, 4>> simplices;
    simplices.reserve(count);
    for (int e = first; e < first + count; ++e) {
      const int* v = mesh.element(e);
      std::array<int, 4> simplex{0, 0, 0, 0};
      const double log_size = std::log(size[e] * ratio(e, share));
      for (int k = 0; k <= dim; ++k) {
        int& local = vertex_of[v[k]];
        if (local < 0) {
          local = static_cast<int>(vertices.size());
          Eigen::Vector3d x = model.rotation.transpose() * mesh.nodes[v[k]];
          if (several) x = model.bodies[b].placement.to_local(x, dim);
          vertices.push_back(x);
          log_sum.push_back(0);
          weight.push_back(0);
        }
        log_sum[local] += log_size;
        weight[local] += 1;
        simplex[k] = local;
      }
      simplices.push_back(simplex);
    }
    std::vector<double> vertex_size(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) vertex_size[i] = std::exp(log_sum[i] / weight[i]);
    auto locator = std::make_shared<const PointLocator>(dim, std::move(vertices), std::move(simplices));
    next.size_fields[b] = [locator, vertex_size = std::move(vertex_size)](const Eigen::Vector3d& x) {
      return locator->interpolate(x, vertex_size);
    };
  }
  return next;
}

}  // namespace contactqp::detail
