#include "hertz_levels.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "contactqp/errors.hpp"

namespace contactqp::bench {

const std::vector<HertzLevel>& hertz_levels() {
  static const std::vector<HertzLevel> levels = {
      {0.2, 0.01},    {0.1, 0.005},     {0.05, 0.0025},   {0.02, 0.002},    {0.01, 0.001},
      {0.004, 0.001}, {0.0028, 0.0007}, {0.0018, 0.0005}, {0.0013, 0.0004},
  };
  return levels;
}

std::string hertz_scene_text(const HertzLevel& level) {
  std::ifstream file(std::string(CONTACTQP_SOURCE_DIR) + "/scenes/hertz.json");
  std::ostringstream text;
  text << file.rdbuf();
  nlohmann::json scene = nlohmann::json::parse(text.str());
  scene["description"] = "scenes/hertz.json with body.mesh.size = " + std::to_string(level.size) +
                         " and contact_size = " + std::to_string(level.contact_size) + " (benchmarks/scaling)";
  scene["body"]["mesh"]["size"] = level.size;
  scene["body"]["mesh"]["contact_size"] = level.contact_size;
  return scene.dump(2) + "\n";
}

std::vector<int> parse_levels(const std::string& text, const std::string& field) {
  std::vector<int> levels;
  const int count = static_cast<int>(hertz_levels().size());
  if (text == "all") {
    for (int k = 0; k < count; ++k) levels.push_back(k);
    return levels;
  }
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const long k = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || k < 0 || k >= count)
      throw InputError(field, "= \"" + text + "\": must be \"all\" or level numbers 0 to " + std::to_string(count - 1) +
                                  " separated by commas");
    levels.push_back(static_cast<int>(k));
  }
  return levels;
}

void make_directory(const std::string& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
    throw InputError("--out", "= " + directory + ": cannot create the directory (" + error.message() + ")");
}

}  // namespace contactqp::bench
