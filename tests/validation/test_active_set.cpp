// The active-set backend on the contact-condensed problem: the condensed operator against a
// dense B K⁻¹ Bᵀ, agreement with the other backends on Hertz, the matrix-free fallback, the
// timings it promises, and the linear-solve reference (--no-contact).
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "contactqp/backends/active_set.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

QuadraticProgram hertz_qp(const std::string& patch = "{}") {
  Model model = build_model(parse_scene(patched_scene("scenes/hertz.json", patch)));
  return assemble_qp(model);
}

// 995 DOFs: CHOLMOD factors it simplicial; scenes/hertz.json (3730 DOFs) goes supernodal.
const char* const kCoarse = R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.01}}})";

SolveOptions active_set(double tol) {
  SolveOptions options;
  options.backend = Backend::ActiveSet;
  options.tol = tol;
  return options;
}

}  // namespace

TEST_CASE("condense() gives B K⁻¹ Bᵀ and B K⁻¹ f of a dense solve (simplicial factor)", "[validation][active_set]") {
  const QuadraticProgram qp = hertz_qp(kCoarse);
  const CholeskyFactor factor(qp.K);
  REQUIRE(factor.ok());
  CHECK_FALSE(factor.supernodal());
  const Eigen::MatrixXd K(qp.K), Bt(qp.B.transpose());
  const Eigen::LLT<Eigen::MatrixXd> dense(K);
  const Eigen::MatrixXd S = Bt.transpose() * dense.solve(Bt);
  const Eigen::VectorXd c = Bt.transpose() * dense.solve(qp.f);

  const Condensation condensed = factor.condense(qp.B, qp.f);
  CHECK((condensed.S - S).norm() <= 1e-10 * S.norm());
  CHECK((condensed.c - c).norm() <= 1e-10 * c.norm());
  CHECK(condensed.S == condensed.S.transpose());
  CHECK(condensed.reached_columns < qp.n_dofs());
  // A scaled view of the factor (standing for 4K) condenses to S/4.
  CHECK((factor.scaled(4.0)->condense(qp.B, qp.f).S - S / 4).norm() <= 1e-10 * S.norm());
}

TEST_CASE("condense() agrees with one solve per row on a supernodal factor, for any ordering",
          "[validation][active_set]") {
  const Ordering ordering = GENERATE(Ordering::Auto, Ordering::Amd, Ordering::Metis);
  const QuadraticProgram qp = hertz_qp();
  const CholeskyFactor factor(qp.K, ordering);
  REQUIRE(factor.ok());
  CAPTURE(factor.ordering_name());
  CHECK(factor.supernodal());
  CHECK(factor.ordering_name() == (ordering == Ordering::Metis ? "metis" : "amd"));
  const Condensation condensed = factor.condense(qp.B, qp.f);
  const Eigen::MatrixXd Bt(qp.B.transpose());
  const Eigen::MatrixXd S = qp.B * factor.solve_columns(Bt);
  CHECK((condensed.S - S).norm() <= 1e-10 * S.norm());
  CHECK((condensed.c - qp.B * factor.solve(qp.f)).norm() <= 1e-10 * condensed.c.norm());
  // Only the elimination-tree paths of the candidate rows are visited.
  CHECK(condensed.reached_columns < qp.n_dofs() / 2);
  CHECK(condensed.peak_entries <= condensed.entries);
}

TEST_CASE("active_set agrees with Uzawa (and Ipopt when built in) on the Hertz scene", "[validation][active_set]") {
  const QuadraticProgram qp = hertz_qp();
  const SolveResult r = solve(qp, active_set(1e-10));
  INFO(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(r.iterations <= 15);
  const Certificate c = certify(qp, r.u, r.lambda, r.K_factor.get());
  CHECK(c.kkt_max() < 1e-12);
  CHECK(std::abs(c.relative_gap) < 1e-12);

  std::vector<Backend> references = {Backend::Uzawa};
  try {
    const Backend ipopt = parse_backend("ipopt");  // on the branches that have it
    if (backend_available(ipopt)) references.push_back(ipopt);
  } catch (const InputError&) {
  }
  for (Backend reference : references) {
    CAPTURE(to_string(reference));
    SolveOptions options = options_for(reference, 1e-10);
    options.K_factor = r.K_factor;
    const SolveResult other = solve(qp, options);
    REQUIRE(other.status == Status::Converged);
    // The compare tolerances: u to 1e-6 and λ to 1e-5, relative.
    CHECK(relative_difference_inf(other.u, r.u) < 1e-6);
    CHECK(relative_difference_inf(other.lambda, r.lambda) < 1e-5);
  }
}

TEST_CASE("active_set reports its phases, and solve is their sum", "[validation][active_set]") {
  const SolveResult r = solve(hertz_qp(), active_set(1e-8));
  REQUIRE(r.status == Status::Converged);
  for (const char* phase : {"factorize", "condense", "iterate", "recover", "solve", "total"}) {
    CAPTURE(phase);
    CHECK(r.timings.has(phase));
  }
  CHECK(r.timings.get("solve") ==
        Approx(r.timings.get("condense") + r.timings.get("iterate") + r.timings.get("recover")));
  CHECK(r.diagnostics.at("dense") == 1);
  CHECK(r.diagnostics.at("active_constraints") == 51);
}

TEST_CASE("over the dense limit, active_set applies S matrix-free and says so", "[validation][active_set]") {
  const QuadraticProgram qp = hertz_qp(kCoarse);
  const SolveResult dense = solve(qp, active_set(1e-10));
  SolveOptions options = active_set(1e-10);
  options.set(ActiveSetOptions{1000});  // 16 m² bytes > 1000 for any m > 7
  const SolveResult matrix_free = solve(qp, options);
  INFO(matrix_free.message);
  REQUIRE(matrix_free.status == Status::Converged);
  CHECK(matrix_free.diagnostics.at("dense") == 0);
  CHECK(matrix_free.message.find("matrix-free") != std::string::npos);
  CHECK(relative_difference_inf(matrix_free.lambda, dense.lambda) < 1e-8);
  CHECK(relative_difference_inf(matrix_free.u, dense.u) < 1e-9);
  CHECK(matrix_free.iterations == dense.iterations);
}

TEST_CASE("active_set needs few iterations on every Hertz mesh", "[validation][active_set]") {
  const std::string patch = GENERATE(
      as<std::string>{}, kCoarse, "{}", R"({"body": {"mesh": {"size": 0.05, "contact_size": 0.001}}})",
      R"({"body": {"mesh": {"order": 2}}})", R"({"body": {"symmetry": false}, "load": {"value": [0.0, -0.016]}})");
  CAPTURE(patch);
  const SolveResult r = solve(hertz_qp(patch), active_set(1e-8));
  INFO(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(r.iterations <= 15);
}

TEST_CASE("active_set keeps ≤ 15 iterations on fine Hertz meshes", "[.slow][active_set]") {
  const std::string patch = GENERATE(as<std::string>{}, R"({"body": {"mesh": {"size": 0.01, "contact_size": 0.0005}}})",
                                     R"({"body": {"mesh": {"size": 0.004, "contact_size": 0.0002}}})");
  CAPTURE(patch);
  const QuadraticProgram qp = hertz_qp(patch);
  const SolveResult r = solve(qp, active_set(1e-8));
  INFO(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(r.iterations <= 15);
  CHECK(certify(qp, r.u, r.lambda, r.K_factor.get()).kkt_max() < 1e-8);
}

TEST_CASE("solve_without_contact gives u = K⁻¹f with the same factorisation path", "[validation][active_set]") {
  const QuadraticProgram qp = hertz_qp(kCoarse);
  const SolveResult r = solve_without_contact(qp, SolveOptions{});
  REQUIRE(r.status == Status::Converged);
  const Eigen::VectorXd exact = Eigen::MatrixXd(qp.K).llt().solve(qp.f);
  CHECK(relative_difference_inf(r.u, exact) < 1e-12);
  CHECK(r.lambda.size() == qp.n_constraints());
  CHECK(r.lambda.isZero(0));
  CHECK(r.timings.has("factorize"));
  CHECK(r.timings.has("solve"));
  // Reusing the factor of a contact solve skips the factorisation.
  SolveOptions reuse;
  reuse.K_factor = solve(qp, active_set(1e-8)).K_factor;
  const SolveResult again = solve_without_contact(qp, reuse);
  CHECK_FALSE(again.timings.has("factorize"));
  CHECK(relative_difference_inf(again.u, exact) < 1e-12);
}

TEST_CASE("contactqp solve --no-contact reports the linear solve like any solve", "[validation][active_set][cli]") {
  TemporaryDirectory directory;
  const CliRun solved =
      run_cli("solve " + source_path("scenes/hertz.json") + " --no-contact --json " + directory.path("r.json"));
  CAPTURE(solved.out, solved.err);
  REQUIRE(solved.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(read_text(directory.path("r.json")));
  CHECK(result["status"] == "converged");
  CHECK(result["backend"] == "none");
  CHECK(result["no_contact"] == true);
  CHECK(result["contact"]["total_force"] == 0.0);
  CHECK(result["timings"]["factorize"].get<double>() > 0);
  CHECK(result["timings"]["solve"].get<double>() > 0);
  CHECK_FALSE(result.contains("hertz"));
  CHECK(solved.err.empty());
}

TEST_CASE("contactqp solve --backend active_set writes the phase timings, and bad options exit 2",
          "[validation][active_set][cli]") {
  TemporaryDirectory directory;
  const std::string scene = source_path("scenes/hertz.json");
  const CliRun run = run_cli("solve " + scene + " --backend active_set --json " + directory.path("r.json"));
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(read_text(directory.path("r.json")));
  CHECK(result["backend"] == "active_set");
  for (const char* phase : {"factorize", "condense", "iterate", "recover", "solve"})
    CHECK(result["timings"].contains(phase));

  const CliRun matrix_free = run_cli("solve " + scene + " --backend active_set --backend-option max_dense_mb=0.01");
  CHECK(matrix_free.exit_status == 0);
  CHECK(matrix_free.out.find("matrix-free") != std::string::npos);
  const CliRun bad = run_cli("solve " + scene + " --backend active_set --backend-option max_dense_mb=-1 --json " +
                             directory.path("bad.json"));
  CHECK(bad.exit_status == 2);
  CHECK(bad.err.find("max_dense_mb") != std::string::npos);
  const CliRun unknown = run_cli("solve " + scene + " --backend active_set --backend-option rho=2");
  CHECK(unknown.exit_status == 2);
  CHECK(unknown.err.find("valid: max_dense_mb") != std::string::npos);
  // Keys addressed to another backend are left to it.
  const CliRun addressed = run_cli("solve " + scene + " --backend active_set --backend-option ipopt.print_level=5");
  CHECK(addressed.exit_status == 0);
}

TEST_CASE("SolveOptions::ordering reaches the factorisation and does not change the answer",
          "[validation][active_set]") {
  const QuadraticProgram qp = hertz_qp();
  const SolveResult amd = solve(qp, active_set(1e-10));
  SolveOptions options = active_set(1e-10);
  options.ordering = Ordering::Metis;
  const SolveResult metis = solve(qp, options);
  REQUIRE(amd.status == Status::Converged);
  REQUIRE(metis.status == Status::Converged);
  CHECK(amd.K_factor->ordering_name() == "amd");  // the default
  CHECK(metis.K_factor->ordering_name() == "metis");
  CHECK(relative_difference_inf(metis.u, amd.u) < 1e-12);
  CHECK(relative_difference_inf(metis.lambda, amd.lambda) < 1e-10);
  CHECK(parse_ordering("auto", "--ordering") == Ordering::Auto);
  CHECK_THROWS_WITH(parse_ordering("nd", "--ordering"), Catch::Matchers::Contains("valid: auto, amd, metis"));
  const CliRun bad = run_cli("solve " + source_path("scenes/hertz.json") + " --ordering colamd");
  CHECK(bad.exit_status == 2);
  CHECK(bad.err.find("--ordering") != std::string::npos);
}
