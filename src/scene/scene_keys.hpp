// Every key of the scene format, section by section (scene_keys.cpp holds the table). The
// table serves three purposes:
//  - check_scene_keys() finds a key the format does not have, at any depth, before any reader
//    runs, so a misspelt or renamed key is reported as unknown (with the nearest valid key),
//    never as the key it should have been missing;
//  - each JsonObject knows its section, and a reader that asks for a key the table does not
//    list is a programming error (std::logic_error): a new key is added here or nowhere;
//  - scene_words() lists every key and every value that selects keys ("shape", "type"), which
//    the fuzzer's dictionary must hold (tests/unit/test_scene_keys.cpp).
// A new section (a key whose value is an object, or an array of objects) is a Section here and
// a Key with `section` set in its parent; the readers then get all of the above for free.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace contactqp::detail {

struct Section;

struct Key {
  std::string name;
  const Section* section = nullptr;  // when the value is an object of its own, or an array of them
  int dim = 0;                       // 2 or 3 when only 2D or 3D scenes have the key; 0 for both
  bool required = false;             // for hints: an unknown key likely stands for a missing required one
};

// A required key (the readers say "is missing" without it).
Key must(std::string name, const Section* section = nullptr, int dim = 0);

// The keys one JSON object may hold. Keys that depend on a choice made in the same object
// ("shape": "rectangle" has width and height, "half_disc" a radius) are in `variants`, one
// list per value of the key named `selector`.
struct Section {
  std::string context;  // how a message names where a key is not valid ("for a mesh file"); may be empty
  std::vector<Key> keys;
  std::string selector;
  std::map<std::string, std::vector<Key>> variants;
  std::map<std::string, int> variant_dims;  // a variant of one dimension only (a "rectangle" body: 2)

  // The keys valid in `object` (this section's JSON object): the common keys and, when the
  // selector names a variant, that variant's; when it names none (missing, misspelt, or a
  // variant of the other dimension, which the reader names as such), every variant's, so that
  // only keys the section never has are unknown. `dim` 2 or 3 leaves out the keys of the other
  // dimension; 0 keeps them.
  std::vector<const Key*> valid_keys(const nlohmann::json& object, int dim = 0) const;
  // The variant `object` selects, or "" (as valid_keys decides).
  std::string chosen_variant(const nlohmann::json& object, int dim = 0) const;
};

const Section& scene_section();  // the document root
const Section& body_section();   // "body", and the shape of each "bodies" entry

// The section of the object at a field path ("load[2]", "bodies[0].material"): the first
// match along the path (variants included), or nullptr when no section has that path.
const Section* section_at(const std::string& path);

// Throws InputError naming the first key of the scene `document` that its section does not
// have, shallowest first, with a hint: the nearest valid key by spelling, else the required
// key the object lacks ("material.poisson is not a valid key; did you mean \"material.nu\"?").
// Values of the wrong type are left to the readers.
void check_scene_keys(const nlohmann::json& document);

// Every key of the format and every value of a selector, sorted, without repeats.
std::vector<std::string> scene_words();

}  // namespace contactqp::detail
