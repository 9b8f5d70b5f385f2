// The backend registry: a backend is one file that registers itself here, and everything that
// names or lists backends reads the registrations — the name table (to_string, parse_backend),
// the CLI's names and help, `compare`, available_backends() and Python's contactqp.Backend.
//
// The built-in backends register from their own files (solvers/uzawa.cpp, ...; docs/style.md,
// "Adding a backend"); a program or a test registers its own with register_backend(), or for
// one scope with ScopedBackendRegistration:
//
//   BackendRegistration toy;
//   toy.name = "toy";
//   toy.summary = "projected gradient on the dual, for QPs of a few rows";
//   toy.solve = [](const QuadraticProgram& qp, const SolveOptions& options) { ... };
//   SolveOptions options;
//   options.backend = register_backend(toy);   // or parse_backend("toy"), --backend toy
//   solve(qp, options);
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/friction.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

struct BackendRegistration {
  // The name the CLI, the scenes, the JSON and Python use: lower case, [a-z][a-z0-9_]*, unique.
  // Python spells the constant in upper case (contactqp.Backend.ACTIVE_SET).
  std::string name;
  // One line saying what the method is, for the CLI's help, Python's docstrings and the docs.
  std::string summary;
  // Where listings put it (all_backends(), compare's rows, the help): ascending, then in the
  // order of registration. The built-ins take 10, 20, ..., 60.
  int order = 1000;
  // False when the library it needs was not built into this copy: it is still named and
  // listed (all_backends()), and solve() refuses it as bad input.
  bool available = true;
  // The problems it solves (friction.hpp); solve() refuses any other kind as bad input.
  std::vector<ProblemKind> problem_kinds = {ProblemKind::Frictionless};
  // With friction, the most tangential directions per contact row it solves: 2 (2D and 3D), or
  // 1 (2D only: nlopt, whose bounds hold an interval but not a disc). solve() refuses more.
  int max_friction_directions = 2;
  // With friction, its iteration limit when the caller leaves SolveOptions::max_iterations at
  // kDefaultMaxIterations (a larger value; 0: that default). Plain Uzawa's sticking rows, which
  // never leave the working set, converge at the rate of S's smallest eigenvalue: one Tresca
  // solve of scenes/mindlin-cylinders.json takes it 18326 steps at tol 1e-10.
  int friction_max_iterations = 0;
  // The backend options it reads (--backend-option key=value, a scene's solver.options), for
  // the help and for the default check below.
  std::vector<std::string> option_names;
  // True when it also takes its library's own options by their native names (Ipopt's): then
  // option_names lists only the common ones and check_options checks the rest.
  bool library_options = false;
  // Throws InputError on a backend option (key or value) it does not accept; called before any
  // work. Empty: every key addressed to it must be one of option_names (any value).
  std::function<void(const SolveOptions&)> check_options;
  // The method: receives a validated QP of a kind it supports (internally scaled unless
  // SolveOptions::scale is false) and returns u and λ; solve() unscales, guards against
  // non-finite output and releases nothing it did not make. Required when available.
  std::function<SolveResult(const QuadraticProgram&, const SolveOptions&)> solve;
};

// Registers a backend; throws InputError (field "backend") when the name is malformed or
// already registered, or when an available backend has no solve. Thread-safe.
Backend register_backend(BackendRegistration registration);
// Removes a registration (a Backend value naming it stays printable; solve() then refuses it).
void unregister_backend(Backend backend);

// A registration for the lifetime of one object: a test's backend that other tests iterating
// over available_backends() never see.
class ScopedBackendRegistration {
 public:
  explicit ScopedBackendRegistration(BackendRegistration registration)
      : backend_(register_backend(std::move(registration))) {}
  ~ScopedBackendRegistration() { unregister_backend(backend_); }
  ScopedBackendRegistration(const ScopedBackendRegistration&) = delete;
  ScopedBackendRegistration& operator=(const ScopedBackendRegistration&) = delete;

  Backend backend() const { return backend_; }

 private:
  Backend backend_;
};

// The registration of a backend; InputError (field "backend") when none is registered by its name.
std::shared_ptr<const BackendRegistration> backend_registration(Backend backend);

bool backend_available(Backend backend);  // registered, and its library was built in
// The available backends, in listing order; with a kind, those that solve it.
std::vector<Backend> available_backends();
std::vector<Backend> available_backends(ProblemKind kind);
bool backend_supports(Backend backend, ProblemKind kind);  // false for a backend not registered
// The same for one QP: its kind and, with friction, its dimension (max_friction_directions).
bool backend_solves(Backend backend, const QuadraticProgram& qp);
std::vector<Backend> available_backends(const QuadraticProgram& qp);

}  // namespace contactqp
