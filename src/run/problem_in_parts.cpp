// The registered ways of holding a QP in parts (problem_in_parts.hpp).
#include "run/problem_in_parts.hpp"

#include <mutex>
#include <vector>

#include "qp/builtins.hpp"

namespace contactqp::detail {
namespace {

struct Registered {
  std::mutex mutex;
  std::vector<PartsAssembly> assemblies;
};

Registered& registered() {
  static Registered all;
  return all;
}

}  // namespace

void register_parts_assembly(PartsAssembly assembly) {
  Registered& r = registered();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.assemblies.push_back(std::move(assembly));
}

std::shared_ptr<ProblemInParts> assemble_in_parts(Model& model, const SolveOptions& options) {
  register_builtins();
  std::vector<PartsAssembly> assemblies;
  {
    Registered& r = registered();
    std::lock_guard<std::mutex> lock(r.mutex);
    assemblies = r.assemblies;
  }
  for (const PartsAssembly& assembly : assemblies)
    if (assembly.takes(options)) return assembly.assemble(model, options);
  return nullptr;
}

}  // namespace contactqp::detail
