// The Hertz meshes of the scaling benchmarks: scenes/hertz.json with its element sizes refined,
// from 1e3 to 1e6 DOFs.
#pragma once

#include <string>
#include <vector>

#include "contactqp/scene.hpp"

namespace contactqp::bench {

struct HertzLevel {
  double size;          // body.mesh.size: far from the contact (units of R)
  double contact_size;  // body.mesh.contact_size: along the candidate arc
};

// Level k has about 2.2^k × 1e3 DOFs: 995, 1767, 3375, 7337, 23467, 1.2e5, 2.4e5, 5.7e5, 1.1e6.
const std::vector<HertzLevel>& hertz_levels();

// scenes/hertz.json with the level's sizes, as JSON text (written beside the results).
std::string hertz_scene_text(const HertzLevel& level);

// "0,3,5" -> {0, 3, 5}; "all" -> every level. Throws InputError naming `field` otherwise.
std::vector<int> parse_levels(const std::string& text, const std::string& field);

// Creates `directory` (and parents); throws InputError("--out", ...) when it cannot.
void make_directory(const std::string& directory);

}  // namespace contactqp::bench
