// How the registrations built into a library (its backends, and the solvers of K it offers) are
// found, although a static archive drops every object file nothing refers to.
//
// A file that registers something defines its registration with
//
//     CONTACTQP_BUILTIN(uzawa) { register_backend(...); }
//
// at namespace scope. CMake (cmake/builtins.cmake) finds that line in the library's sources and
// generates the library's list of them: a function calling each, which the list hands to
// add_builtin_list() when the program is loaded, and a symbol that the library's users link
// with -Wl,--undefined, so that the list — and through it every registering file — is always
// linked. The registries run the lists on their first use (register_builtins()), never during
// static initialisation, so a registration may use anything its own file initialises.
#pragma once

// The function that registers one file's built-ins: contactqp::detail::builtin_<id>().
#define CONTACTQP_BUILTIN(id)   \
  namespace contactqp::detail { \
  void builtin_##id();          \
  }                             \
  void contactqp::detail::builtin_##id()

namespace contactqp::detail {

// One library's generated list; constant-initialised, so it can be added before anything else.
struct BuiltinList {
  void (*register_all)();
  BuiltinList* next;
};

// Adds a library's list (its generated file calls it while the program is loaded).
void add_builtin_list(BuiltinList& list) noexcept;

// Runs every list once, on the first call from any thread; the registries call it before
// every look-up. A list added later (a library loaded afterwards) runs when it is added.
void register_builtins();

}  // namespace contactqp::detail
