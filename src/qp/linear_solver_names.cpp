// The names of the solvers of K and of the orderings, for options, scenes and messages. Apart
// from the rest of linear_solver.cpp so that the scene parser (and its fuzzer) needs no solver.
#include <utility>

#include "contactqp/errors.hpp"
#include "contactqp/linear_solver.hpp"

namespace contactqp {
namespace {

const std::pair<LinearSolverKind, const char*> kLinearSolverNames[] = {{LinearSolverKind::Cholmod, "cholmod"},
                                                                       {LinearSolverKind::Petsc, "petsc"}};

const std::pair<Ordering, const char*> kOrderingNames[] = {
    {Ordering::Auto, "auto"}, {Ordering::Amd, "amd"}, {Ordering::Metis, "metis"}};

template <typename Value, size_t N>
Value parse_name(const std::pair<Value, const char*> (&table)[N], const std::string& name, const std::string& field,
                 const char* what) {
  std::string valid;
  for (const auto& [value, known] : table) {
    if (name == known) return value;
    valid += (valid.empty() ? "" : ", ") + std::string(known);
  }
  throw InputError(field, "= \"" + name + "\": unknown " + what + "; valid: " + valid);
}

template <typename Value, size_t N>
std::string name_of(const std::pair<Value, const char*> (&table)[N], Value value) {
  for (const auto& [known, name] : table)
    if (known == value) return name;
  return "unknown";
}

}  // namespace

std::string to_string(LinearSolverKind kind) { return name_of(kLinearSolverNames, kind); }
std::string to_string(Ordering ordering) { return name_of(kOrderingNames, ordering); }

LinearSolverKind parse_linear_solver(const std::string& name, const std::string& field) {
  return parse_name(kLinearSolverNames, name, field, "linear solver");
}

Ordering parse_ordering(const std::string& name, const std::string& field) {
  return parse_name(kOrderingNames, name, field, "ordering");
}

std::vector<LinearSolverKind> all_linear_solvers() {
  std::vector<LinearSolverKind> list;
  for (const auto& entry : kLinearSolverNames) list.push_back(entry.first);
  return list;
}

}  // namespace contactqp
