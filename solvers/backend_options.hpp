// Backend options given as text (--backend-option key=value, a scene's solver.options): which
// keys a backend reads, and the strict parsing of their values (the norms and number formats the
// backends' messages share come with it, from src/qp/norms.hpp and contactqp/number_format.hpp).
//
// A key may be addressed to one backend by prefixing its name, "ipopt.print_level": `compare`
// runs several backends from one command line, and each reads only its own keys and the
// unaddressed ones.
#pragma once

#include <map>
#include <string>

#include "contactqp/number_format.hpp"
#include "contactqp/qp.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {

using OptionMap = std::map<std::string, std::string>;

// The options `backend` reads: unaddressed keys, and keys "<its name>.key" with the prefix
// removed (these win over an unaddressed key of the same name). Keys addressed to another
// backend are left out.
OptionMap options_for(Backend backend, const OptionMap& options);

// For a backend that takes no options: InputError on the first key addressed to it.
void reject_options(Backend backend, const OptionMap& options, const std::string& hint);

// The field an error message names for a backend option: "backend option print_level".
std::string option_field(const std::string& key);

// The whole text must be a finite number (an integer); InputError naming `field` otherwise.
double parse_number(const std::string& text, const std::string& field);
int parse_integer(const std::string& text, const std::string& field);

}  // namespace contactqp::detail
