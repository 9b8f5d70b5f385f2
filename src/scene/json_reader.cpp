#include "json_reader.hpp"

#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"

namespace contactqp::detail {
namespace {

std::string type_name(const nlohmann::json& value) {
  if (value.is_null()) return "null";
  if (value.is_boolean()) return "a boolean";
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  return "an object";
}

}  // namespace

std::string describe(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

double as_number(const nlohmann::json& value, const std::string& path) {
  if (!value.is_number())
    throw InputError(path, "= " + describe(value) + ": must be a number, not " + type_name(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InputError(path, "= " + describe(value) + ": must be finite");
  return x;
}

JsonObject::JsonObject(const nlohmann::json& value, std::string path) : json_(value), path_(std::move(path)) {
  if (!json_.is_object())
    throw InputError(path_.empty() ? "scene" : path_,
                     "= " + describe(json_) + ": must be an object, not " + type_name(json_));
}

bool JsonObject::has(const std::string& key) const {
  known_.insert(key);
  return json_.contains(key);
}

std::string JsonObject::path_of(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

const nlohmann::json& JsonObject::required(const std::string& key) {
  if (!has(key)) {
    // A misspelt key is the likelier cause than a forgotten one: name the unknown key that is
    // closest to the missing one ("materail" for "material") before saying it is missing.
    for (const auto& item : json_.items()) {
      if (read_.count(item.key()) || known_.count(item.key())) continue;
      if (nearest(item.key(), {key}) == key)
        throw InputError(path_of(item.key()), "is not a valid key; did you mean \"" + path_of(key) + "\"?");
    }
    throw InputError(path_of(key), "is missing: it is required");
  }
  read_.insert(key);
  return json_.at(key);
}

const nlohmann::json& JsonObject::value(const std::string& key) { return required(key); }

double JsonObject::number(const std::string& key) { return as_number(required(key), path_of(key)); }

std::optional<double> JsonObject::optional_number(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return number(key);
}

int JsonObject::integer(const std::string& key) {
  const nlohmann::json& v = required(key);
  const double x = as_number(v, path_of(key));
  if (x != std::floor(x) || std::abs(x) > 2e9)
    throw InputError(path_of(key), "= " + describe(v) + ": must be an integer");
  return static_cast<int>(x);
}

std::optional<int> JsonObject::optional_integer(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return integer(key);
}

std::string JsonObject::string(const std::string& key) {
  const nlohmann::json& v = required(key);
  if (!v.is_string()) throw InputError(path_of(key), "= " + describe(v) + ": must be a string, not " + type_name(v));
  return v.get<std::string>();
}

std::optional<std::string> JsonObject::optional_string(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::optional<bool> JsonObject::optional_boolean(const std::string& key) {
  if (!has(key)) return std::nullopt;
  const nlohmann::json& v = required(key);
  if (!v.is_boolean())
    throw InputError(path_of(key), "= " + describe(v) + ": must be true or false, not " + type_name(v));
  return v.get<bool>();
}

JsonObject JsonObject::object(const std::string& key) { return JsonObject(required(key), path_of(key)); }

void JsonObject::finish(const std::vector<std::string>& also_valid) const {
  std::vector<std::string> valid(known_.begin(), known_.end());
  valid.insert(valid.end(), also_valid.begin(), also_valid.end());
  for (const auto& item : json_.items()) {
    if (read_.count(item.key())) continue;
    const std::string hint = nearest(item.key(), valid);
    throw InputError(
        path_of(item.key()),
        "is not a valid key" + (hint.empty() ? std::string() : "; did you mean \"" + path_of(hint) + "\"?"));
  }
}

}  // namespace contactqp::detail
