// The adaptive run's sizes and warm start (docs/adaptive.md): the size field it hands Gmsh interpolates the
// planned vertex sizes exactly where the old mesh is (the point locator), and plan_next_mesh() meets its error
// model's target with the elements it predicts.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "mesh/point_locator.hpp"
#include "run/adaptive_sizes.hpp"
#include "run/adaptive_warm_start.hpp"
#include "test_support.hpp"

using namespace contactqp;
using detail::NextMesh;
using detail::NextMeshLimits;
using detail::plan_next_mesh;
using detail::PointLocator;

namespace {

// Hertz's half cylinder (R = 1, pushed by 0.016 onto a plane) meshed with these sizes, active_set.
Scene cylinder_scene(double size, double contact_size) {
  return parse_scene(R"({
    "model": "plane_strain", "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "half_disc", "radius": 1.0, "symmetry": true, "mesh": {"size": )" +
                     std::to_string(size) + R"(, "contact_size": )" + std::to_string(contact_size) + R"(}},
    "load": {"type": "displacement", "boundary": "top", "value": [null, -0.016]},
    "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
    "solver": {"backend": "active_set", "tol": 1e-10}})");
}

}  // namespace

TEST_CASE("the point locator interpolates a linear field exactly and clamps outside the mesh", "[adaptive]") {
  SECTION("2D: the unit square in two triangles") {
    const auto f = [](const Eigen::Vector3d& x) { return 1 + x.x() + 2 * x.y(); };
    std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<double> size;
    for (const auto& v : vertices) size.push_back(f(v));
    const PointLocator locator(2, vertices, {{0, 1, 2, 0}, {0, 2, 3, 0}});
    const auto lookup = [&](const Eigen::Vector3d& x) { return locator.interpolate(x, size); };
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.3, 0.2, 0), Eigen::Vector3d(0.9, 0.95, 0),
                                     Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(0, 1, 0)})
      CHECK(lookup(x) == Approx(f(x)).epsilon(1e-14));
    // Just outside a side (a curved boundary between old nodes): the side's value.
    CHECK(lookup(Eigen::Vector3d(1 + 1e-3, 0.5, 0)) == Approx(f(Eigen::Vector3d(1, 0.5, 0))).epsilon(1e-3));
    CHECK(lookup(Eigen::Vector3d(0.25, -0.01, 0)) == Approx(f(Eigen::Vector3d(0.25, 0, 0))).epsilon(1e-2));
    // Far outside: never beyond the vertex values.
    const double far = lookup(Eigen::Vector3d(5, 7, 0));
    CHECK(far >= 1 - 1e-12);
    CHECK(far <= 4 + 1e-12);
  }
  SECTION("3D: a tetrahedron") {
    const auto f = [](const Eigen::Vector3d& x) { return 0.5 + x.x() - x.y() + 3 * x.z(); };
    std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    std::vector<double> size;
    for (const auto& v : vertices) size.push_back(f(v));
    const PointLocator locator(3, vertices, {{0, 1, 2, 3}});
    const auto lookup = [&](const Eigen::Vector3d& x) { return locator.interpolate(x, size); };
    const Eigen::Vector3d x(0.2, 0.3, 0.1);
    CHECK(lookup(x) == Approx(f(x)).epsilon(1e-14));
  }
}

TEST_CASE("the point locator finds the triangle of a strongly graded mesh", "[adaptive]") {
  // The unit square on a grid graded geometrically toward x = y = 0 (ratio 1.4: sizes from 0.3
  // down to 4e-7), two triangles per cell: an adapted mesh's contact zone, where a uniform grid
  // of cells put thousands of simplices in one. A linear field is interpolated exactly at
  // points spread over every scale, so each lies in the triangle returned.
  const int n = 40;
  std::vector<double> t(n + 1);
  for (int i = 0; i <= n; ++i) t[i] = (std::pow(1.4, i) - 1) / (std::pow(1.4, n) - 1);
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) vertices.emplace_back(t[i], t[j], 0);
  std::vector<std::array<int, 4>> simplices;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      simplices.push_back({a, b, c, 0});
      simplices.push_back({a, c, d, 0});
    }
  const auto f = [](const Eigen::Vector3d& x) { return 1 + x.x() + 2 * x.y(); };
  std::vector<double> values;
  for (const auto& v : vertices) values.push_back(f(v));
  const PointLocator locator(2, vertices, simplices);
  for (int k = 0; k < 2000; ++k) {
    // Log-uniform in each coordinate, from 1e-6 to 1.
    const Eigen::Vector3d x(std::pow(10.0, -6.0 * ((k * 7919) % 1000) / 1000.0),
                            std::pow(10.0, -6.0 * ((k * 104729) % 997) / 997.0), 0);
    CAPTURE(x.transpose());
    CHECK(locator.interpolate(x, values) == Approx(f(x)).epsilon(1e-12));
  }
}

TEST_CASE("the point locator files a cell under its own box: the candidates near a curved side", "[adaptive]") {
  // Two triangles of the unit square; the right one's box widened to x = 1.2 (a quadratic
  // cell whose side bulges out there). A point at x = 1.1 lies outside every simplex, inside that
  // box: the widened cell is among its candidates.
  const std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<std::array<int, 4>> simplices = {{0, 1, 2, 0}, {0, 2, 3, 0}};
  const std::vector<PointLocator::Box> boxes = {{{0, 0, 0}, {1.2, 1, 0}}, {{0, 0, 0}, {1, 1, 0}}};
  const PointLocator curved(2, vertices, simplices, boxes);
  const std::vector<int> beside = curved.near(Eigen::Vector3d(1.1, 0.5, 0));
  CHECK(beside == std::vector<int>{0});  // the widened box only
  // Inside the square the candidates include the simplex that holds the point.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.8, 0.1, 0), Eigen::Vector3d(0.1, 0.8, 0)}) {
    const std::vector<int> candidates = curved.near(x);
    CHECK(std::find(candidates.begin(), candidates.end(), curved.locate(x).simplex) != candidates.end());
  }
  // Outside every box: the nearest simplices.
  const std::vector<int> far = curved.near(Eigen::Vector3d(-3, 0.5, 0));
  CHECK(std::find(far.begin(), far.end(), 1) != far.end());
  CHECK_THROWS_AS(PointLocator(2, vertices, simplices, {boxes[0]}), std::invalid_argument);
}

TEST_CASE("the next mesh's plan meets its error model's target with the elements it predicts", "[adaptive]") {
  // A coarse Hertz cylinder; the indicators replaced by equal ones, for which the plan is known
  // by hand: every element's size times r, η² falling like r^(2p) = r² (P1 in 2D) and the
  // elements growing like r^(-2).
  const Scene scene = cylinder_scene(0.25, 0.25);
  const RunReport report = run_scene(scene);
  const int n = report.model->mesh.n_elements();
  const Eigen::VectorXd equal = Eigen::VectorXd::Constant(n, 1e-3);
  const double eta = 1e-3 * std::sqrt(n);
  NextMeshLimits limits;
  limits.max_size = {10.0};  // not binding
  limits.max_growth = 10;
  NextMesh next = plan_next_mesh(*report.model, equal, eta / 2, limits);  // r = 1/2
  CHECK(next.estimate == Approx(eta / 2).epsilon(1e-6));
  CHECK(next.elements == Approx(4.0 * n).epsilon(1e-6));
  limits.max_growth = 2;  // the growth binds: r = 1/√2
  next = plan_next_mesh(*report.model, equal, eta / 2, limits);
  CHECK(next.elements == Approx(2.0 * n).epsilon(1e-6));
  CHECK(next.estimate == Approx(eta / std::sqrt(2.0)).epsilon(1e-6));
  REQUIRE(next.size_fields.size() == 1);
  REQUIRE(next.size_fields[0]);
  // An element's vertices take the geometric mean of their elements' sizes: between the
  // smallest and the largest planned size.
  const double size = next.size_fields[0](Eigen::Vector3d(0.2, 0.5, 0));
  CHECK(size > 0.25 / std::sqrt(2.0) * 0.3);
  CHECK(size < 0.25 / std::sqrt(2.0) * 3);
  // A larger indicator asks for smaller elements there.
  Eigen::VectorXd peaked = equal;
  peaked[0] = 1e-1;
  next = plan_next_mesh(*report.model, peaked, eta, limits);
  const int* v = report.model->mesh.element(0);
  const Eigen::Vector3d centre =
      (report.model->mesh.nodes[v[0]] + report.model->mesh.nodes[v[1]] + report.model->mesh.nodes[v[2]]) / 3;
  double elsewhere = 0;
  for (int e = 1; e < n; ++e) {
    const int* w = report.model->mesh.element(e);
    elsewhere = std::max(
        elsewhere,
        next.size_fields[0](
            (report.model->mesh.nodes[w[0]] + report.model->mesh.nodes[w[1]] + report.model->mesh.nodes[w[2]]) / 3));
  }
  CHECK(next.size_fields[0](centre) < elsewhere);
}

TEST_CASE("the warm start of an adaptive cycle carries u and lambda to a mesh", "[adaptive]") {
  // On the mesh the answer came from, linear elements: every node is a vertex, so the
  // interpolated displacement is the answer's, and λ_i = p_i · w_i gives back each row's force.
  const Scene scene = cylinder_scene(0.1, 0.01);
  const RunReport report = run_scene(scene);
  REQUIRE(report.result.status == Status::Converged);
  const detail::WarmStart warm(*report.model, *report.qp, report.result);
  const InitialGuess guess = warm(*report.model, *report.qp);
  REQUIRE(guess.u.size() == report.result.u.size());
  CHECK((guess.u - report.result.u).cwiseAbs().maxCoeff() <= 1e-14 * report.result.u.cwiseAbs().maxCoeff());
  REQUIRE(guess.lambda.size() == report.result.lambda.size());
  CHECK((guess.lambda - report.result.lambda).cwiseAbs().maxCoeff() <= 1e-12 * report.result.lambda.maxCoeff());

  // Started from it, the same problem needs no step of the active set beyond the first check.
  SolveOptions options = scene.solver;
  options.initial = guess;
  const SolveResult again = solve(*report.qp, options);
  CHECK(again.status == Status::Converged);
  CHECK(again.iterations <= 1);
  CHECK(report.result.iterations > again.iterations);
}
