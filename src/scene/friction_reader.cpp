// `friction` sections — on the contact boundary, an obstacle, a pair or a body's boundary entry —
// and the rules that hold across them: one law per scene, no row given friction twice.
#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp {

FrictionLaw Scene::friction_law() const {
  if (contact.friction) return contact.friction->law;
  for (const ObstacleSpec& obstacle : obstacles)
    if (obstacle.friction) return obstacle.friction->law;
  for (const ContactPair& pair : pairs)
    if (pair.friction) return pair.friction->law;
  for (const ObstacleContactSpec& entry : obstacle_contacts)
    if (entry.friction) return entry.friction->law;
  return FrictionLaw::None;
}

namespace detail {
namespace {

std::string law_name(FrictionLaw law) { return law == FrictionLaw::Coulomb ? "Coulomb" : "Tresca"; }

// Every friction section of the scene, in the order it was written.
std::vector<const FrictionSpec*> friction_specs(const Scene& scene) {
  std::vector<const FrictionSpec*> specs;
  if (scene.contact.friction) specs.push_back(&*scene.contact.friction);
  for (const ObstacleSpec& obstacle : scene.obstacles)
    if (obstacle.friction) specs.push_back(&*obstacle.friction);
  for (const ContactPair& pair : scene.pairs)
    if (pair.friction) specs.push_back(&*pair.friction);
  for (const ObstacleContactSpec& entry : scene.obstacle_contacts)
    if (entry.friction) specs.push_back(&*entry.friction);
  return specs;
}

}  // namespace

FrictionSpec read_friction(JsonObject friction) {
  FrictionSpec spec;
  spec.path = friction.path();
  const bool coulomb = friction.has("coefficient"), tresca = friction.has("threshold");
  if (coulomb && tresca)
    throw InputError(spec.path, "has both \"coefficient\" (Coulomb's μ) and \"threshold\" (Tresca's s): give one");
  if (!coulomb && !tresca) {
    friction.finish();  // a misspelt key is the likelier cause: name it first
    throw InputError(spec.path, "needs \"coefficient\": μ (Coulomb) or \"threshold\": s (Tresca, force per area)");
  }
  if (coulomb) {
    spec.law = FrictionLaw::Coulomb;
    spec.coefficient = friction.number("coefficient");
    require(spec.coefficient >= 0, friction.path_of("coefficient"), spec.coefficient, "must be ≥ 0");
  } else {
    spec.law = FrictionLaw::Tresca;
    spec.threshold = friction.number("threshold");
    require(spec.threshold >= 0, friction.path_of("threshold"), spec.threshold, "must be ≥ 0 (force per area)");
  }
  friction.finish();
  return spec;
}

void check_friction(const Scene& scene) {
  const std::vector<const FrictionSpec*> specs = friction_specs(scene);
  for (const FrictionSpec* spec : specs)
    if (spec->law != specs.front()->law)
      throw InputError(spec->path, "is " + law_name(spec->law) + "'s law and " + specs.front()->path + " " +
                                       law_name(specs.front()->law) + "'s: one friction law per scene");
  // The rows against an obstacle come from one boundary: friction there is given once.
  const FrictionSpec* boundary = scene.contact.friction ? &*scene.contact.friction : nullptr;
  for (const ObstacleContactSpec& entry : scene.obstacle_contacts)
    if (!boundary && entry.friction) boundary = &*entry.friction;
  if (!boundary) return;
  for (const ObstacleSpec& obstacle : scene.obstacles)
    if (obstacle.friction)
      throw InputError(obstacle.friction->path, "and " + boundary->path + " both apply to the rows against " +
                                                    obstacle.path + ": give friction in one place");
}

}  // namespace detail
}  // namespace contactqp
