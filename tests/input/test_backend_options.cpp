// Backend options (--backend-option key=value, solver.options in a scene): each backend
// accepts its own keys with values of the right type, rejects anything else as bad input
// naming the key, and a key addressed to one backend ("ipopt.max_iter") reaches only it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "contactqp/backends/nlopt.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

SolveOptions with_option(Backend backend, const std::string& key, const std::string& value) {
  SolveOptions options = options_for(backend, 1e-8);
  options.backend_options[key] = value;
  return options;
}

}  // namespace

TEST_CASE("Ipopt options: unknown keys and bad values are input errors naming the key", "[input][ipopt]") {
  struct Case {
    std::string key, value, names;
  };
  const Case cases[] = {
      {"print_lvl", "5", "backend option print_lvl"},
      {"max_iter", "many", "backend option max_iter = \"many\": must be an integer"},
      {"max_iter", "-3", "backend option max_iter = -3"},
      {"tol", "0", "backend option tol = 0: Ipopt requires > 0"},
      {"tol", "1e-8x", "must be a finite number"},
      {"mu_strategy", "fast", "valid: monotone, adaptive"},
  };
  const QuadraticProgram qp = random_qp(4, 3, 1);
  for (const Case& c : cases) {
    CAPTURE(c.key, c.value);
    CHECK_THROWS_AS(solve(qp, with_option(Backend::Ipopt, c.key, c.value)), InputError);
    CHECK_THROWS_WITH(validate_options(with_option(Backend::Ipopt, c.key, c.value)),
                      Catch::Matchers::Contains(c.names));
  }
}

TEST_CASE("Ipopt options reach Ipopt with their types", "[input][ipopt]") {
  const QuadraticProgram qp = random_qp(8, 6, 3);
  SECTION("an integer: max_iter overrides max_iterations") {
    const SolveResult r = solve(qp, with_option(Backend::Ipopt, "max_iter", "2"));
    CHECK(r.status == Status::MaxIterations);
    CHECK(r.iterations == 2);
    CHECK(r.message.find("Maximum_Iterations_Exceeded") != std::string::npos);
  }
  SECTION("a string and a number, addressed to Ipopt") {
    SolveOptions options = with_option(Backend::Ipopt, "ipopt.mu_strategy", "monotone");
    options.backend_options["ipopt.mu_init"] = "0.01";
    const SolveResult r = solve(qp, options);
    CHECK(r.status == Status::Converged);
  }
  SECTION("keys addressed to another backend are not Ipopt's business") {
    const SolveResult r = solve(qp, with_option(Backend::Ipopt, "nlopt.algorithm", "LD_MMA"));
    CHECK(r.status == Status::Converged);
  }
}

TEST_CASE("Ipopt never reads ./ipopt.opt", "[input][ipopt]") {
  TemporaryDirectory directory;
  std::ofstream(directory.path("ipopt.opt")) << "max_iter 1\n";
  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(directory.path(""));
  const SolveResult r = solve(random_qp(8, 6, 4), options_for(Backend::Ipopt, 1e-8));
  std::filesystem::current_path(previous);
  CHECK(r.status == Status::Converged);
  CHECK(r.iterations > 1);
}

TEST_CASE("NLopt options: algorithm and memory, nothing else", "[input][nlopt]") {
  const QuadraticProgram qp = random_qp(8, 6, 5);
  const ExactSolution exact = solve_by_enumeration(qp);
  SECTION("every algorithm on offer solves a small QP") {
    const std::string algorithm = GENERATE("LD_LBFGS", "LD_CCSAQ", "LD_MMA", "LD_SLSQP", "ld_mma");
    CAPTURE(algorithm);
    SolveOptions options = with_option(Backend::Nlopt, "algorithm", algorithm);
    options.tol = 1e-6;
    const SolveResult r = solve(qp, options);
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(relative_difference(r.u, exact.u) < 1e-4);
  }
  SECTION("the API's NloptOptions, and memory") {
    SolveOptions options = with_option(Backend::Nlopt, "memory", "3");
    CHECK(options.get<NloptOptions>().algorithm == NloptOptions::Algorithm::Lbfgs);  // unset: the defaults
    options.set(NloptOptions{NloptOptions::Algorithm::Ccsaq});
    CHECK(SolveOptions(options).get<NloptOptions>().algorithm == NloptOptions::Algorithm::Ccsaq);  // copies carry it
    const SolveResult r = solve(qp, options);
    CHECK(r.status == Status::Converged);
    CHECK(r.message.find("LD_CCSAQ") != std::string::npos);
  }
  SECTION("bad keys and values") {
    CHECK_THROWS_WITH(validate_options(with_option(Backend::Nlopt, "algorithm", "LN_COBYLA")),
                      Catch::Matchers::Contains("valid: LD_LBFGS, LD_CCSAQ, LD_MMA, LD_SLSQP"));
    CHECK_THROWS_WITH(validate_options(with_option(Backend::Nlopt, "memory", "-1")),
                      Catch::Matchers::Contains("memory"));
    CHECK_THROWS_WITH(validate_options(with_option(Backend::Nlopt, "print_level", "5")),
                      Catch::Matchers::Contains("backend option print_level"));
    CHECK_NOTHROW(validate_options(with_option(Backend::Nlopt, "ipopt.print_level", "5")));
  }
}

TEST_CASE("NLopt reports an evaluation budget it ran out of", "[input][nlopt]") {
  SolveOptions options = options_for(Backend::Nlopt, 1e-12);
  options.max_iterations = 5;
  const SolveResult r = solve(random_qp(8, 6, 6), options);
  CHECK(r.status == Status::MaxIterations);
  CHECK(r.iterations == 5);
  CHECK(r.u.allFinite());
}

TEST_CASE("Uzawa takes no backend options, but lets others' pass", "[input][uzawa]") {
  CHECK_THROWS_WITH(validate_options(with_option(Backend::Uzawa, "rho", "0.5")),
                    Catch::Matchers::Contains("backend option rho") && Catch::Matchers::Contains("--rho"));
  CHECK_NOTHROW(validate_options(with_option(Backend::Uzawa, "ipopt.max_iter", "5")));
}

TEST_CASE("a scene's solver.options are backend options", "[input][scene]") {
  const Scene scene = parse_scene(patched_scene(
      "scenes/hertz.json",
      R"({"solver": {"backend": "ipopt", "options": {"max_iter": 50, "mu_strategy": "monotone", "tol": 1e-9}}})"));
  CHECK(scene.solver.backend == Backend::Ipopt);
  CHECK(scene.solver.backend_options.at("max_iter") == "50");
  CHECK(scene.solver.backend_options.at("mu_strategy") == "monotone");
  CHECK(std::stod(scene.solver.backend_options.at("tol")) == 1e-9);
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"options": {"sb": true}}})")),
                    Catch::Matchers::Contains("solver.options.sb"));
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"options": [1]}})")),
                    Catch::Matchers::Contains("solver.options"));
}
