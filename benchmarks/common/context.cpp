#include "context.hpp"

#include <array>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <thread>

namespace contactqp::bench {
namespace {

// The first line a shell command prints, or "" (git missing, not a checkout, ...).
std::string first_line_of(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r")) {
    std::array<char, 256> buffer{};
    if (std::fgets(buffer.data(), buffer.size(), pipe)) out = buffer.data();
    ::pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

std::string context_json(const std::string& benchmark, const std::string& extra) {
  const std::string git = "git -C \"" CONTACTQP_SOURCE_DIR "\" ";
  std::array<char, 32> date{};
  const std::time_t now = std::time(nullptr);
  std::strftime(date.data(), date.size(), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
#ifdef __clang__
  const char* compiler = "clang " __clang_version__;
#else
  const char* compiler = "gcc " __VERSION__;
#endif
  nlohmann::json context = {{"benchmark", benchmark},
                            {"git_revision", first_line_of(git + "rev-parse HEAD")},
                            {"git_dirty", !first_line_of(git + "status --porcelain --untracked-files=no").empty()},
                            {"compiler", compiler},
                            {"build_type", CONTACTQP_BUILD_TYPE},
                            {"cores", std::thread::hardware_concurrency()},
                            {"load_average", first_line_of("cut -d' ' -f1-3 /proc/loadavg")},
                            {"date_utc", date.data()}};
  context.merge_patch(nlohmann::json::parse(extra));
  return context.dump(2) + "\n";
}

}  // namespace contactqp::bench
