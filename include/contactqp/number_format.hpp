// How numbers become text, in one place: printf-style formatting into a std::string, a number
// with a given count of significant digits for messages and tables, and a CSV field that is
// empty rather than NaN or Inf (docs/style.md: never NaN in output).
#pragma once

#include <string>

namespace contactqp {

// printf into a std::string, of any length.
std::string format(const char* pattern, ...) __attribute__((format(printf, 1, 2)));

// x with `digits` significant digits (%.*g): number(0.1234567) is "0.123457",
// number(1e-12, 4) is "1e-12".
std::string number(double x, int digits = 6);

// A number in a message, to four significant digits: "1.218e-08".
inline std::string short_number(double x) { return number(x, 4); }

// A CSV field: number(x, digits), and an empty field for NaN or Inf.
std::string csv_number(double x, int digits = 10);

}  // namespace contactqp
