// Strict reading of a JSON object: every key must be consumed, every value must have the
// expected type; errors name the full field path ("body.mesh.size") and the value. Each
// object knows its section of the scene format (scene_keys.hpp): asking for a key the section
// does not list is a programming error (std::logic_error), so the table stays complete.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "qp/words.hpp"

namespace contactqp::detail {

struct Section;

class JsonObject {
 public:
  // `path` is the field path of this object ("" for the document root, "load[2]"); its
  // section is the one at that path (section_at()).
  JsonObject(const nlohmann::json& value, std::string path);

  bool has(const std::string& key) const;
  const std::string& path() const { return path_; }  // this object's field path
  std::string path_of(const std::string& key) const;

  double number(const std::string& key);
  std::optional<double> optional_number(const std::string& key);
  int integer(const std::string& key);
  std::optional<int> optional_integer(const std::string& key);
  std::string string(const std::string& key);
  std::optional<std::string> optional_string(const std::string& key);
  std::optional<bool> optional_boolean(const std::string& key);
  const nlohmann::json& value(const std::string& key);  // any type; marks the key as read
  JsonObject object(const std::string& key);

  // Throws on the first key that was never read, suggesting the nearest key this object
  // knows (every key asked for, present or not, plus `also_valid`). check_scene_keys() has
  // already refused the keys the section does not have: what is left is a key the section has
  // but this reader does not read in this case (a 2D key in a 3D scene, "pair" in a one-body
  // contact).
  void finish(const std::vector<std::string>& also_valid = {}) const;

 private:
  JsonObject(const nlohmann::json& value, std::string path, const Section* section);
  const nlohmann::json& required(const std::string& key);
  void require_listed(const std::string& key) const;  // std::logic_error unless the section has `key`
  const nlohmann::json& json_;
  std::string path_;
  const Section* section_;
  std::set<std::string> read_;
  mutable std::set<std::string> known_;  // every key asked for: the valid keys of this object
};

// The JSON document of a scene file, or InputError naming `source`: a syntax error, a number
// beyond double range, nesting deeper than 64 levels, or a key twice in one object (JSON
// parsers keep one of the two silently; a scene means one).
nlohmann::json parse_json(const std::string& text, const std::string& source);

// A one-line rendering of a JSON value for error messages (long values are shortened).
std::string describe(const nlohmann::json& value);

// A JSON number as double, or InputError naming `path` when it is not a finite number.
double as_number(const nlohmann::json& value, const std::string& path);

}  // namespace contactqp::detail
