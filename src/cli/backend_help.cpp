// The backends as the help lists them, from their registrations (contactqp/backend.hpp).
#include <algorithm>

#include "commands.hpp"
#include "contactqp/backend.hpp"
#include "contactqp/errors.hpp"

namespace contactqp::cli {

std::string backend_names() {
  std::vector<std::string> names;
  for (Backend backend : available_backends()) names.push_back(to_string(backend));
  return join(names);
}

std::string backends_help() {
  std::size_t width = 0;
  for (Backend backend : all_backends()) width = std::max(width, to_string(backend).size());
  std::string text = "Backends (--backend-option key=value, or <backend>.key=value for one of them):\n";
  for (Backend backend : all_backends()) {
    const auto registration = backend_registration(backend);
    std::string line =
        "  " + registration->name + std::string(width + 2 - registration->name.size(), ' ') + registration->summary;
    if (!registration->available) line += " (not built into this copy)";
    // The problems it solves (available_backends(ProblemKind)): friction is refused elsewhere.
    std::vector<std::string> kinds;
    for (ProblemKind kind : registration->problem_kinds) kinds.push_back(to_string(kind));
    line += "; solves " + join(kinds);
    if (registration->problem_kinds.size() > 1 && registration->max_friction_directions < 2)
      line += " (friction in 2D only)";
    if (!registration->option_names.empty())
      line += "; options " + join(registration->option_names) +
              (registration->library_options ? " (and any other of its library's own)" : "");
    text += line + "\n";
  }
  return text;
}

}  // namespace contactqp::cli
