// The seam between the backends and the solver of K (linear_solver.hpp): names and bad input,
// the generic multi-column solve and condensation against CHOLMOD's own, scaled views, the
// choice reaching a scene and the command line, and the near-null space the FE side fills.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/solve.hpp"
#include "qp/dense_decompositions.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

QuadraticProgram hertz_qp(const std::string& patch = "{}") {
  Model model = build_model(parse_scene(patched_scene("scenes/hertz.json", patch)));
  return assemble_qp(model);
}

// A LinearSolver that solves with CHOLMOD but keeps the interface's generic solve_columns()
// and condense(): the generic path, measured against CHOLMOD's restricted forward solve.
class GenericPath final : public LinearSolver {
 public:
  explicit GenericPath(const SparseMatrix& A) : factor_(std::make_shared<CholeskyFactor>(A)) {}
  bool ok() const override { return factor_->ok(); }
  const std::string& message() const override { return factor_->message(); }
  int size() const override { return factor_->size(); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override { return factor_->solve(b); }
  using LinearSolver::solve;
  LinearSolverStatistics statistics() const override { return factor_->statistics(); }

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override { return factor_->scaled(c); }

 private:
  std::shared_ptr<CholeskyFactor> factor_;
};

}  // namespace

TEST_CASE("linear solver names parse, and a bad one names its field and the valid names", "[unit][linear_solver]") {
  CHECK(parse_linear_solver("cholmod", "--linear-solver") == LinearSolverKind::Cholmod);
  CHECK(parse_linear_solver("petsc", "--linear-solver") == LinearSolverKind::Petsc);
  for (LinearSolverKind kind : all_linear_solvers()) CHECK(parse_linear_solver(to_string(kind), "x") == kind);
  CHECK_THROWS_WITH(
      parse_linear_solver("mumps", "--linear-solver"),
      Catch::Matchers::StartsWith("--linear-solver = \"mumps\"") && Catch::Matchers::Contains("valid: cholmod, petsc"));
  CHECK(SolveOptions{}.linear_solver == LinearSolverKind::Cholmod);  // the default
  CHECK(linear_solver_available(LinearSolverKind::Cholmod));
}

TEST_CASE("the generic condense() and solve_columns() agree with CHOLMOD's own", "[unit][linear_solver]") {
  const QuadraticProgram qp = hertz_qp();
  const CholeskyFactor factor(qp.K);
  const GenericPath generic(qp.K);
  REQUIRE(factor.ok());
  const Condensation fast = factor.condense(qp.B, qp.f);
  const Condensation slow = generic.condense(qp.B, qp.f);  // one solve per row, in blocks
  REQUIRE(qp.n_constraints() > 32);                        // more than one block
  CHECK((slow.S - fast.S).norm() <= 1e-10 * fast.S.norm());
  CHECK((slow.c - fast.c).norm() <= 1e-10 * fast.c.norm());
  CHECK(slow.S == slow.S.transpose());
  const Eigen::MatrixXd rhs = Eigen::MatrixXd(qp.B.transpose()).leftCols(5);
  CHECK((generic.LinearSolver::solve_columns(rhs) - factor.solve_columns(rhs)).norm() <=
        1e-12 * factor.solve_columns(rhs).norm());
  // A direct solver ignores the guess of the warm-started form.
  const LinearSolver& seam = factor;
  CHECK(seam.solve(qp.f, Eigen::VectorXd::Constant(qp.n_dofs(), 1e3)) == factor.solve(qp.f));
  // A scaled view through the interface stands for 4K.
  CHECK((seam.scaled(4.0)->solve(qp.f) - factor.solve(qp.f) / 4).norm() <= 1e-12 * factor.solve(qp.f).norm());
}

TEST_CASE("CHOLMOD reports its statistics through the interface", "[unit][linear_solver]") {
  const QuadraticProgram qp = hertz_qp();
  const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-8));
  REQUIRE(r.status == Status::Converged);
  REQUIRE(r.K_factor);
  const LinearSolverStatistics s = r.K_factor->statistics();
  CHECK(s.name == "cholmod");
  CHECK(s.factor_nonzeros >= qp.K.nonZeros() / 2);  // L holds at least K's lower triangle
  CHECK(s.iterations == 0);
  CHECK(s.solves >= r.iterations);  // one solve per Uzawa iteration at least
  CHECK(s.setup_seconds > 0);
  CHECK(r.K_factor->ordering_name() == "amd");
}

TEST_CASE("solver.linear_solver in a scene, and bad values there and on the command line", "[unit][linear_solver]") {
  CHECK(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"linear_solver": "cholmod"}})"))
            .solver.linear_solver == LinearSolverKind::Cholmod);
  CHECK(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"linear_solver": "petsc"}})"))
            .solver.linear_solver == LinearSolverKind::Petsc);
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"linear_solver": "lu"}})")),
                    Catch::Matchers::StartsWith("solver.linear_solver = \"lu\"") &&
                        Catch::Matchers::Contains("valid: cholmod, petsc"));
  // A near miss of the key is an unknown key, with the hint.
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"linear_solvers": "petsc"}})")),
                    Catch::Matchers::Contains("solver.linear_solver"));
  const std::string scene = source_path("scenes/hertz.json");
  for (const char* command : {"solve", "compare"}) {
    CAPTURE(command);
    const CliRun run = run_cli(std::string(command) + " " + scene + " --linear-solver lu");
    CHECK(run.exit_status == 2);
    CHECK(run.err.find("--linear-solver = \"lu\"") != std::string::npos);
    CHECK(run.err.find("valid: cholmod, petsc") != std::string::npos);
  }
}

TEST_CASE("assemble_qp fills the rigid-body modes on the free DOFs, in the DOF frames", "[unit][linear_solver]") {
  // hertz-rotated: a rotated scene whose prescribed nodes keep DOF frames along the scene's axes.
  for (const char* name : {"scenes/hertz.json", "scenes/hertz-rotated.json"}) {
    CAPTURE(name);
    Model model = build_model(load_scene(source_path(name)));
    const QuadraticProgram qp = assemble_qp(model);
    REQUIRE(qp.near_null_space.rows() == qp.n_dofs());
    REQUIRE(qp.near_null_space.cols() == 3);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(qp.near_null_space);
    CHECK(svd.singularValues()[2] > 1e-3 * svd.singularValues()[0]);  // three independent modes
    // Back in the global frame (full_displacement rotates DOF frames to x, y), each mode is a
    // rigid motion a + ω e_z × x at every node whose two components are free.
    model.prescribed.setZero();
    for (int mode = 0; mode < 3; ++mode) {
      CAPTURE(mode);
      const Eigen::VectorXd full = full_displacement(model, qp.near_null_space.col(mode));
      std::vector<int> nodes;
      for (int node = 0; node < model.mesh.n_nodes(); ++node)
        if (model.free_index[2 * node] >= 0 && model.free_index[2 * node + 1] >= 0) nodes.push_back(node);
      REQUIRE(nodes.size() > 3);
      Eigen::MatrixXd A(2 * nodes.size(), 3);
      Eigen::VectorXd y(2 * nodes.size());
      for (size_t k = 0; k < nodes.size(); ++k) {
        const Eigen::Vector2d x = model.mesh.nodes[nodes[k]].head<2>();
        A.row(2 * k) << 1, 0, -x.y();
        A.row(2 * k + 1) << 0, 1, x.x();
        y.segment<2>(2 * k) = full.segment<2>(2 * nodes[k]);
      }
      const Eigen::VectorXd motion = A.colPivHouseholderQr().solve(y);
      CHECK((A * motion - y).cwiseAbs().maxCoeff() <= 1e-12 * y.cwiseAbs().maxCoeff());
      CHECK(y.cwiseAbs().maxCoeff() > 0);
    }
  }
}
