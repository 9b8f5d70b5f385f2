#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contactqp/errors.hpp"
#include "scene_keys.hpp"

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

// Where the parser is, for naming a repeated key: one frame per open object or array.
struct Frame {
  bool array = false;
  int index = -1;              // array: the entry being read
  std::string key;             // object: the key being read
  std::set<std::string> keys;  // object: the keys read so far
};

std::string path_of(const std::vector<Frame>& frames) {
  std::string path;
  for (size_t i = 1; i < frames.size(); ++i) {
    const Frame& parent = frames[i - 1];
    if (parent.array)
      path += "[" + std::to_string(parent.index) + "]";
    else
      path += (path.empty() ? "" : ".") + parent.key;
  }
  return path;
}

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& source) {
  using Event = nlohmann::json::parse_event_t;
  // Printing a value in an error message recurses once per level: 100 000 nested brackets
  // overflowed the stack. A scene nests a few levels; refuse deep nesting while parsing.
  constexpr int kMaxDepth = 64;
  std::vector<Frame> frames;
  const nlohmann::json::parser_callback_t watch = [&](int depth, Event event, nlohmann::json& parsed) {
    if (depth > kMaxDepth && (event == Event::object_start || event == Event::array_start))
      throw InputError(
          source, "is not a scene: arrays and objects nested deeper than " + std::to_string(kMaxDepth) + " levels");
    const bool starts_value = event == Event::value || event == Event::object_start || event == Event::array_start;
    if (starts_value && !frames.empty() && frames.back().array) ++frames.back().index;
    if (event == Event::object_start || event == Event::array_start) {
      frames.emplace_back();
      frames.back().array = event == Event::array_start;
    }
    if (event == Event::object_end || event == Event::array_end) frames.pop_back();
    if (event == Event::key) {
      Frame& object = frames.back();
      object.key = parsed.get<std::string>();
      if (!object.keys.insert(object.key).second) {
        const std::string path = path_of(frames);
        throw InputError(path.empty() ? object.key : path + "." + object.key,
                         "appears twice in one object; give each key once");
      }
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, watch);
  } catch (const nlohmann::json::exception& error) {  // a syntax error, or a number beyond double range (1e999)
    std::string what = error.what();
    const auto bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    // The parser quotes what it read last, which may be any bytes: keep the message readable.
    for (char& c : what)
      if (static_cast<unsigned char>(c) >= 0x80) c = '?';
    throw InputError(source, "is not valid JSON: " + what);
  }
}

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

JsonObject::JsonObject(const nlohmann::json& value, std::string path) : JsonObject(value, path, section_at(path)) {}

JsonObject::JsonObject(const nlohmann::json& value, std::string path, const Section* section)
    : json_(value), path_(std::move(path)), section_(section) {
  if (!section_)
    throw std::logic_error("the scene reader reads an object at \"" + path_ +
                           "\", which src/scene/scene_keys.cpp does not list");
  if (!json_.is_object())
    throw InputError(path_.empty() ? "scene" : path_,
                     "= " + describe(json_) + ": must be an object, not " + type_name(json_));
}

void JsonObject::require_listed(const std::string& key) const {
  for (const Key* listed : section_->valid_keys(json_))
    if (listed->name == key) return;
  throw std::logic_error("the scene reader asks for \"" + path_of(key) +
                         "\", which src/scene/scene_keys.cpp does not list");
}

bool JsonObject::has(const std::string& key) const {
  require_listed(key);
  known_.insert(key);
  return json_.contains(key);
}

std::string JsonObject::path_of(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

const nlohmann::json& JsonObject::required(const std::string& key) {
  // check_scene_keys() has refused every key the format does not have, so a misspelt key
  // ("materail", "poisson") was reported as unknown before any key could be missing.
  if (!has(key)) throw InputError(path_of(key), "is missing: it is required");
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

JsonObject JsonObject::object(const std::string& key) {
  const nlohmann::json& value = required(key);
  // The child's section as this object's variant has it ("body.mesh" of a .geo file or of a
  // generated shape), not the first at that path.
  for (const Key* listed : section_->valid_keys(json_))
    if (listed->name == key && listed->section) return JsonObject(value, path_of(key), listed->section);
  return JsonObject(value, path_of(key));
}

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
