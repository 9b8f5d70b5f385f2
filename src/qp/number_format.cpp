#include "contactqp/number_format.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace contactqp {

std::string format(const char* pattern, ...) {
  va_list args;
  va_start(args, pattern);
  va_list copy;
  va_copy(copy, args);
  const int length = std::vsnprintf(nullptr, 0, pattern, copy);
  va_end(copy);
  std::string out(length > 0 ? static_cast<size_t>(length) : 0, '\0');
  if (length > 0) std::vsnprintf(out.data(), out.size() + 1, pattern, args);
  va_end(args);
  return out;
}

std::string number(double x, int digits) { return format("%.*g", digits, x); }

std::string csv_number(double x, int digits) { return std::isfinite(x) ? number(x, digits) : std::string(); }

}  // namespace contactqp
