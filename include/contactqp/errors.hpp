// Bad input, as opposed to a solver outcome (docs/style.md §4).
//
// Every check of user input throws InputError before any work is done. The message is one
// line: the field path, the offending value, the rule, and a hint when there is one, e.g.
//   material.nu = 0.5: must lie in (-1, 0.5)
// The command-line tool prints it on stderr and exits with status 2.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactqp {

class InputError : public std::runtime_error {
 public:
  // `field` is a path such as "material.nu" or a file name; `message` is the rest of the line.
  InputError(std::string field, const std::string& message);

  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// A value as the messages write it (12 significant digits: "0.5", "1e-12").
template <class T>
std::string format_value(const T& value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}
// "(x, y)" or "(x, y, z)": the first `dim` components of a point, as format_value writes them.
template <class Vector>
std::string format_point(const Vector& x, int dim) {
  std::string text = "(";
  for (int c = 0; c < dim; ++c) text += (c ? ", " : "") + format_value(x[c]);
  return text + ")";
}
// "a, b, c": a list of valid names in a message.
std::string join(const std::vector<std::string>& words);

// require(nu > -1 && nu < 0.5, "material.nu", nu, "must lie in (-1, 0.5)")
//   throws "material.nu = 0.5: must lie in (-1, 0.5)" when the condition fails.
template <class T>
void require(bool condition, const std::string& field, const T& value, const std::string& rule) {
  if (!condition) throw InputError(field, "= " + format_value(value) + ": " + rule);
}

}  // namespace contactqp
