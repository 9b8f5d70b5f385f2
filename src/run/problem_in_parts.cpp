// The registered ways of holding a QP in parts (problem_in_parts.hpp).
#include "run/problem_in_parts.hpp"

#include <vector>

#include "qp/builtins.hpp"
#include "qp/registrations.hpp"

namespace contactqp::detail {
namespace {

Registrations<PartsAssembly>& parts_assemblies() {
  static Registrations<PartsAssembly> all;
  return all;
}

}  // namespace

void register_parts_assembly(PartsAssembly assembly) { parts_assemblies().add(std::move(assembly)); }

std::shared_ptr<ProblemInParts> assemble_in_parts(Model& model, const SolveOptions& options) {
  register_builtins();
  for (const PartsAssembly& assembly : parts_assemblies().copy())
    if (assembly.takes(options)) return assembly.assemble(model, options);
  return nullptr;
}

}  // namespace contactqp::detail
