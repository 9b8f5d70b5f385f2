// The readers of the scene's sections (scene.cpp composes them). Each consumes one JSON
// object through JsonObject, so that every key is checked and every error names its field.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "contactqp/scene.hpp"
#include "json_reader.hpp"

namespace contactqp::detail {

// [x, y] (dim 2, z = 0) or [x, y, z] (dim 3) as a vector, or InputError naming `path`.
Eigen::Vector3d read_vector(const nlohmann::json& value, const std::string& path, int dim);

// A direction: read_vector, non-zero, normalised.
Eigen::Vector3d read_direction(const nlohmann::json& value, const std::string& path, int dim);

// Throws `path = "value": unknown <what>; valid: a, b; did you mean "a"?`.
[[noreturn]] void unknown_choice(const std::string& path, const std::string& value, const std::string& what,
                                 const std::vector<std::string>& valid);

// A section that may be one object or an array of them ("load": {...} or "load": [{...}]):
// each entry with its field path ("load", "load[2]").
std::vector<std::pair<const nlohmann::json*, std::string>> one_or_many(const nlohmann::json& value,
                                                                       const std::string& path);

// `solver`.
void read_solver(JsonObject solver, SolveOptions& options);

// `material` (E, ν), each error naming the field under the object's path.
Material read_material(JsonObject material);

// bodies_reader.cpp: a scene with a "bodies" list — every body (name, material, shape, loads,
// placement), `contact` (pairs and obstacle boundaries), `obstacle`, `solver` — into `scene`.
void read_bodies(JsonObject& root, Scene& scene, const std::string& source);

// `body`: the shape and its mesh. `source` is the scene file, against whose directory a mesh
// file is resolved.
BodySpec read_body(JsonObject body, const std::string& source, int dim);

// One entry of `load`; `path` is its field path ("load" or "load[2]").
LoadSpec read_load(JsonObject load, const BodySpec& body, int dim);

// One entry of `obstacle`.
ObstacleSpec read_obstacle(JsonObject obstacle, int dim);

// friction_reader.cpp: a `friction` section, {"coefficient": μ} or {"threshold": s}.
FrictionSpec read_friction(JsonObject friction);

// friction_reader.cpp: `steps`, after every load is read (their names are known); and the
// scene-wide rules of friction: one law, and no row given friction twice.
void read_steps(const nlohmann::json& steps, Scene& scene);
void check_friction(const Scene& scene);

// adapt_reader.cpp: `adapt`, {"target": 0.01, "max_dofs": 200000, "max_cycles": 12}.
AdaptSpec read_adapt(JsonObject adapt);

// `transform`.
TransformSpec read_transform(JsonObject transform, int dim);

// With body.symmetry, InputError unless the rest of the scene is mirror-symmetric about x = 0
// (and about y = 0 in 3D), in the scene's own frame, before its transform.
void check_symmetry(const Scene& scene);

// InputError unless `name` is a boundary of a generated shape (mesh bodies are checked once
// their mesh is read).
void require_boundary(const std::string& name, const BodySpec& body, const std::string& path);

}  // namespace contactqp::detail
