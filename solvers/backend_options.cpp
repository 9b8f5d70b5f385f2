#include "backend_options.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "contactqp/errors.hpp"

namespace contactqp::detail {

OptionMap options_for(Backend backend, const OptionMap& options) {
  const std::string own_prefix = to_string(backend) + ".";
  OptionMap mine;
  for (const auto& [key, value] : options) {
    bool addressed = false;
    for (Backend any : all_backends()) addressed = addressed || key.rfind(to_string(any) + ".", 0) == 0;
    if (!addressed) mine[key] = value;
  }
  // Addressed keys last, so that they override an unaddressed key of the same name.
  for (const auto& [key, value] : options)
    if (key.rfind(own_prefix, 0) == 0) mine[key.substr(own_prefix.size())] = value;
  return mine;
}

void reject_options(Backend backend, const OptionMap& options, const std::string& hint) {
  for (const auto& [key, value] : options_for(backend, options))
    throw InputError(option_field(key),
                     "= \"" + value + "\": " + to_string(backend) + " takes no backend options; " + hint);
}

std::string option_field(const std::string& key) { return "backend option " + key; }

double parse_number(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || errno == ERANGE || !std::isfinite(value))
    throw InputError(field, "= \"" + text + "\": must be a finite number");
  return value;
}

int parse_integer(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(begin, &end, 10);
  if (text.empty() || end != begin + text.size() || errno == ERANGE || value < INT_MIN || value > INT_MAX)
    throw InputError(field, "= \"" + text + "\": must be an integer");
  return static_cast<int>(value);
}

}  // namespace contactqp::detail
