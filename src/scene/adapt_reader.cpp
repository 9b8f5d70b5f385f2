// The scene's "adapt" section (scene.hpp, AdaptSpec; docs/adaptive.md).
#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {

AdaptSpec read_adapt(JsonObject adapt) {
  AdaptSpec spec;
  spec.target = adapt.number("target");
  require(spec.target > 0 && spec.target < 1, adapt.path_of("target"), spec.target,
          "must lie in (0, 1): the relative energy error eta/sqrt(2E) wanted, 0.01 for 1%");
  if (auto max_dofs = adapt.optional_integer("max_dofs")) {
    require(*max_dofs > 0, adapt.path_of("max_dofs"), *max_dofs, "must be positive");
    spec.max_dofs = *max_dofs;
  }
  if (auto max_cycles = adapt.optional_integer("max_cycles")) {
    require(*max_cycles >= 1, adapt.path_of("max_cycles"), *max_cycles, "must be at least 1");
    spec.max_cycles = *max_cycles;
  }
  adapt.finish();
  return spec;
}

}  // namespace contactqp::detail
