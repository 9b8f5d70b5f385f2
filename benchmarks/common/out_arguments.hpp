// The command line of the small benchmarks that take only --out DIR and --quick (element_order,
// incompressible), and the CSV path they write in DIR.
#pragma once

#include <string>

namespace contactqp::bench {

struct OutArguments {
  std::string out;     // directory for the CSV and context.json; default out/<name>
  bool quick = false;  // a seconds-long smoke run (ctest)
};

// Parses argv into `arguments`; false (after printing the usage) on anything else.
bool parse_out_arguments(int argc, char** argv, const std::string& name, OutArguments& arguments);

// DIR/file, with DIR created and the path checked for writing (InputError otherwise).
std::string output_path(const std::string& directory, const std::string& file);

}  // namespace contactqp::bench
