// `steps`: an ordered list of load steps, each naming the loads it scales and their factors at
// its end (docs/friction.md, "Load steps").
#include <map>
#include <set>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp {
namespace {

// Every load of the scene in the order load_factors() uses: the scene's, then each body's.
std::vector<const LoadSpec*> all_loads(const Scene& scene) {
  std::vector<const LoadSpec*> loads;
  for (const LoadSpec& load : scene.loads) loads.push_back(&load);
  for (const SceneBody& body : scene.bodies)
    for (const LoadSpec& load : body.loads) loads.push_back(&load);
  return loads;
}

}  // namespace

std::vector<std::vector<double>> load_factors(const Scene& scene) {
  const std::vector<const LoadSpec*> loads = all_loads(scene);
  std::vector<double> factors(loads.size(), 1.0);
  if (scene.steps.empty()) return {factors};
  std::map<std::string, size_t> index;
  for (size_t l = 0; l < loads.size(); ++l)
    if (!loads[l]->name.empty()) {
      index[loads[l]->name] = l;
      factors[l] = 0.0;  // a named load waits for the first step that names it
    }
  std::vector<std::vector<double>> steps;
  for (const LoadStep& step : scene.steps) {
    for (const auto& [name, factor] : step.factors) factors[index.at(name)] = factor;
    steps.push_back(factors);
  }
  return steps;
}

namespace detail {

void read_steps(const nlohmann::json& steps, Scene& scene) {
  if (!steps.is_array() || steps.empty())
    throw InputError("steps", "= " + describe(steps) +
                                  ": must be a non-empty array of steps [{\"factors\": {\"load name\": factor}}, ...]");
  std::vector<std::string> names;
  std::map<std::string, std::string> path_of_name;
  for (const LoadSpec* load : all_loads(scene)) {
    if (load->name.empty()) continue;
    if (path_of_name.count(load->name))
      throw InputError(load->path + ".name", "= \"" + load->name + "\": " + path_of_name[load->name] +
                                                 " has this name too; steps need one load per name");
    path_of_name[load->name] = load->path;
    names.push_back(load->name);
  }
  if (names.empty())
    throw InputError("steps",
                     "scale named loads, and no load has a \"name\"; add \"name\": \"push\" (say) to "
                     "the loads the steps change");
  for (size_t k = 0; k < steps.size(); ++k) {
    const std::string path = "steps[" + std::to_string(k) + "]";
    JsonObject step(steps[k], path);
    LoadStep spec;
    spec.path = path;
    const nlohmann::json& factors = step.value("factors");
    const std::string factors_path = step.path_of("factors");
    if (!factors.is_object() || factors.empty())
      throw InputError(factors_path,
                       "= " + describe(factors) + ": must name at least one load and its factor, {\"push\": 1}");
    for (const auto& [name, value] : factors.items()) {
      if (!path_of_name.count(name)) {
        const std::string hint = nearest(name, names);
        throw InputError(factors_path + "." + name, "is not a load: no load is named \"" + name +
                                                        "\"; loads: " + join(names) +
                                                        (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
      }
      spec.factors.emplace_back(name, as_number(value, factors_path + "." + name));
    }
    step.finish();
    scene.steps.push_back(spec);
  }
}

}  // namespace detail
}  // namespace contactqp
