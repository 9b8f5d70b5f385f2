// context.json beside a benchmark's CSV: git revision, compiler, build type, cores, date.
#pragma once

#include <string>

namespace contactqp::bench {

// The JSON text of the machine context; `extra` (a JSON object's text) is merged in.
std::string context_json(const std::string& benchmark, const std::string& extra = "{}");

}  // namespace contactqp::bench
