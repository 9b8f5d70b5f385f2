// The backend registry (backend.hpp) and the name table it makes: to_string, parse_backend,
// all_backends, available_backends. The built-ins are registered on first use (builtins.hpp).
#include <algorithm>
#include <mutex>
#include <set>

#include "contactqp/backend.hpp"
#include "contactqp/errors.hpp"
#include "qp/builtins.hpp"
#include "qp/words.hpp"

namespace contactqp {

class BackendRegistry {
 public:
  static BackendRegistry& instance() {
    static BackendRegistry registry;
    return registry;
  }

  Backend add(BackendRegistration registration) {
    check(registration);
    std::lock_guard<std::mutex> lock(mutex_);
    if (find(registration.name))
      throw InputError("backend", "= \"" + registration.name + "\": a backend of this name is already registered");
    const Backend backend(*names_.insert(registration.name).first);
    entries_.push_back({std::make_shared<const BackendRegistration>(std::move(registration)), next_sequence_++});
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
      return a.registration->order != b.registration->order ? a.registration->order < b.registration->order
                                                            : a.sequence < b.sequence;
    });
    return backend;
  }

  void remove(Backend backend) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                  [&](const Entry& e) { return e.registration->name == backend.name(); }),
                   entries_.end());
  }

  std::shared_ptr<const BackendRegistration> get(std::string_view name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(name);
  }

  // Every registration with the Backend naming it, in listing order.
  std::vector<std::pair<Backend, std::shared_ptr<const BackendRegistration>>> list() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::pair<Backend, std::shared_ptr<const BackendRegistration>>> out;
    for (const Entry& e : entries_) out.emplace_back(Backend(*names_.find(e.registration->name)), e.registration);
    return out;
  }

 private:
  struct Entry {
    std::shared_ptr<const BackendRegistration> registration;
    long sequence;
  };

  static void check(const BackendRegistration& r) {
    const bool well_formed = !r.name.empty() && r.name[0] >= 'a' && r.name[0] <= 'z' &&
                             std::all_of(r.name.begin(), r.name.end(), [](char c) {
                               return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                             });
    if (!well_formed)
      throw InputError("backend", "= \"" + r.name + "\": a backend's name is lower case, [a-z][a-z0-9_]*");
    if (r.available && !r.solve)
      throw InputError("backend", "= \"" + r.name + "\": an available backend needs a solve");
    if (r.problem_kinds.empty())
      throw InputError("backend", "= \"" + r.name + "\": a backend must solve at least one kind of problem");
  }

  std::shared_ptr<const BackendRegistration> find(std::string_view name) const {
    for (const Entry& e : entries_)
      if (e.registration->name == name) return e.registration;
    return nullptr;
  }

  mutable std::mutex mutex_;
  std::vector<Entry> entries_;  // in listing order
  long next_sequence_ = 0;
  // Every name ever registered, never erased: a Backend refers to its characters.
  std::set<std::string, std::less<>> names_;
};

namespace {

BackendRegistry& registry() {
  detail::register_builtins();
  return BackendRegistry::instance();
}

std::vector<Backend> backends_where(const std::function<bool(const BackendRegistration&)>& keep) {
  std::vector<Backend> list;
  for (const auto& [backend, registration] : registry().list())
    if (keep(*registration)) list.push_back(backend);
  return list;
}

bool supports(const BackendRegistration& registration, ProblemKind kind) {
  return std::find(registration.problem_kinds.begin(), registration.problem_kinds.end(), kind) !=
         registration.problem_kinds.end();
}

bool solves(const BackendRegistration& registration, const QuadraticProgram& qp) {
  return supports(registration, problem_kind(qp)) &&
         (qp.friction.empty() || qp.friction.n_directions <= registration.max_friction_directions);
}

}  // namespace

Backend register_backend(BackendRegistration registration) { return registry().add(std::move(registration)); }

void unregister_backend(Backend backend) { registry().remove(backend); }

std::shared_ptr<const BackendRegistration> backend_registration(Backend backend) {
  auto registration = registry().get(backend.name());
  if (!registration) parse_backend(std::string(backend.name()));  // throws, naming the valid ones
  return registration;
}

std::string to_string(Backend backend) { return std::string(backend.name()); }

std::vector<Backend> all_backends() {
  return backends_where([](const BackendRegistration&) { return true; });
}

Backend parse_backend(const std::string& name, const std::string& field) {
  std::vector<std::string> valid;
  for (const auto& [backend, registration] : registry().list()) {
    if (registration->name == name) return backend;
    valid.push_back(registration->name);
  }
  const std::string hint = detail::nearest(name, valid);
  throw InputError(field, "= \"" + name + "\": unknown backend; valid: " + join(valid) +
                              (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

bool backend_available(Backend backend) {
  const auto registration = registry().get(backend.name());
  return registration && registration->available;
}

std::vector<Backend> available_backends() {
  return backends_where([](const BackendRegistration& r) { return r.available; });
}

std::vector<Backend> available_backends(ProblemKind kind) {
  return backends_where([&](const BackendRegistration& r) { return r.available && supports(r, kind); });
}

bool backend_supports(Backend backend, ProblemKind kind) {
  const auto registration = registry().get(backend.name());
  return registration && supports(*registration, kind);
}

bool backend_solves(Backend backend, const QuadraticProgram& qp) {
  const auto registration = registry().get(backend.name());
  return registration && solves(*registration, qp);
}

std::vector<Backend> available_backends(const QuadraticProgram& qp) {
  return backends_where([&](const BackendRegistration& r) { return r.available && solves(r, qp); });
}

}  // namespace contactqp
