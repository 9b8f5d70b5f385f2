// contactqp compare: the table, the JSON fields, and the exit status that says whether the
// backends converged and agree.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

const char* const kRunFields[] = {"backend",    "status",          "iterations",  "seconds",
                                  "objective",  "dual_objective",  "duality_gap", "kkt_max",
                                  "rel_diff_u", "rel_diff_lambda", "half_width",  "max_pressure"};

std::string all_backends_list() {
  std::string list;
  for (Backend backend : available_backends()) list += (list.empty() ? "" : ",") + to_string(backend);
  return list;
}

}  // namespace

TEST_CASE("compare scenes/hertz.json --tol 1e-10: all converge and agree, exit 0", "[cross_backend][cli]") {
  TemporaryDirectory directory;
  const std::string out = directory.path("compare.json");
  const CliRun run = run_cli("compare " + source_path("scenes/hertz.json") + " --tol 1e-10 --json " + out);
  CAPTURE(run.out, run.err);
  CHECK(run.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(read_text(out));
  REQUIRE(result["runs"].size() == available_backends().size());
  for (const auto& entry : result["runs"]) {
    CAPTURE(entry.dump());
    for (const char* field : kRunFields) CHECK(entry.contains(field));
    CHECK(entry["status"] == "converged");
    CHECK(entry["iterations"].get<int>() > 0);
    CHECK(std::abs(entry["relative_duality_gap"].get<double>()) <= 1e-8);
    CHECK(entry["rel_diff_u"].get<double>() <= 1e-6);
    CHECK(entry["rel_diff_lambda"].get<double>() <= 1e-5);
    CHECK(entry["half_width"].get<double>() == Approx(0.0998).epsilon(0.01));
    // The row is in the table too, with its iteration count.
    const std::string name = entry["backend"];
    CHECK(run.out.find(name) != std::string::npos);
  }
  CHECK(result["agree"] == true);
  // Third-party banners and logs stay silent without --verbose.
  CHECK(run.out.find("This program contains Ipopt") == std::string::npos);
  CHECK(run.out.find("EXIT:") == std::string::npos);
  CHECK(run.err.empty());
  CHECK(result["max_pairwise_rel_diff_u"].get<double>() <= 1e-6);
  CHECK(result["max_pairwise_rel_diff_lambda"].get<double>() <= 1e-5);
  CHECK(result["reference"].is_string());
}

TEST_CASE("compare exits 1 when a backend does not converge, and writes null, not NaN", "[cross_backend][cli]") {
  TemporaryDirectory directory;
  const std::string out = directory.path("compare.json");
  const CliRun run = run_cli("compare " + source_path("scenes/hertz.json") + " --backends " + all_backends_list() +
                             " --tol 1e-10 --max-iterations 3 --json " + out);
  CAPTURE(run.out, run.err);
  CHECK(run.exit_status == 1);
  const std::string text = read_text(out);
  CHECK(text.find("NaN") == std::string::npos);
  CHECK(text.find("nan") == std::string::npos);
  const nlohmann::json result = nlohmann::json::parse(text);
  CHECK(result["agree"] == false);
  bool some_not_converged = false;
  for (const auto& entry : result["runs"]) some_not_converged |= entry["status"] != "converged";
  CHECK(some_not_converged);
}

TEST_CASE("compare with one backend chosen by name", "[cross_backend][cli]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  TemporaryDirectory directory;
  const std::string out = directory.path("compare.json");
  const CliRun run =
      run_cli("compare " + source_path("scenes/hertz.json") + " --backends " + to_string(backend) + " --json " + out);
  CAPTURE(run.out, run.err);
  CHECK(run.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(read_text(out));
  REQUIRE(result["runs"].size() == 1);
  CHECK(result["runs"][0]["backend"] == to_string(backend));
  CHECK(result["runs"][0]["rel_diff_u"].get<double>() == 0.0);
  CHECK(result["reference"] == to_string(backend));
}
