// libFuzzer target: the scene parser on arbitrary bytes. parse_scene() must either return a
// Scene or throw InputError — any other exception, a crash, a hang or a sanitizer report is a
// finding. No meshing: a mesh file the bytes may name is only checked for existence.
#include <cstddef>
#include <cstdint>
#include <string>

#include "contactqp/backend.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"

// No backend is linked into the parser alone: register the built-ins' names (unavailable), so
// that scenes naming them reach the solver keys after solver.backend.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  for (const contactqp::Backend backend :
       {contactqp::Backend::Uzawa, contactqp::Backend::UzawaAccelerated, contactqp::Backend::Ipopt,
        contactqp::Backend::Nlopt, contactqp::Backend::ActiveSet, contactqp::Backend::Petsc}) {
    contactqp::BackendRegistration name_only;
    name_only.name = contactqp::to_string(backend);
    name_only.available = false;
    contactqp::register_backend(name_only);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    contactqp::parse_scene(text, "fuzz/scene.json");
  } catch (const contactqp::InputError&) {
    // Bad input, reported as it should be.
  }
  return 0;
}
