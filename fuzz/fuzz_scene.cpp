// libFuzzer target: the scene parser on arbitrary bytes. parse_scene() must either return a
// Scene or throw InputError — any other exception, a crash, a hang or a sanitizer report is a
// finding. No meshing: a mesh file the bytes may name is only checked for existence.
#include <cstddef>
#include <cstdint>
#include <string>

#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    contactqp::parse_scene(text, "fuzz/scene.json");
  } catch (const contactqp::InputError&) {
    // Bad input, reported as it should be.
  }
  return 0;
}
