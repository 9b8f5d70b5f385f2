#include "contactqp/errors.hpp"

#include <cstdio>

namespace contactqp {
namespace {

// One line, whatever the input held: control characters (a newline inside a JSON string, a
// tab in a file name) are written as escapes, so that the message stays the one line on
// stderr that the command line promises.
std::string one_line(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const unsigned char byte = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\t')
      out += "\\t";
    else if (byte < 0x20 || byte == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", byte);
      out += escape;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

InputError::InputError(std::string field, const std::string& message)
    : std::runtime_error(one_line(field) + " " + one_line(message)), field_(std::move(field)) {}

}  // namespace contactqp
