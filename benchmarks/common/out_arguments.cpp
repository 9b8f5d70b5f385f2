#include "out_arguments.hpp"

#include <filesystem>
#include <iostream>

#include "contactqp/io.hpp"

namespace contactqp::bench {

bool parse_out_arguments(int argc, char** argv, const std::string& name, OutArguments& arguments) {
  arguments.out = "out/" + name;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--out" && i + 1 < argc) {
      arguments.out = argv[++i];
    } else if (argument == "--quick") {
      arguments.quick = true;
    } else {
      std::cerr << "usage: bench_" << name << " [--out DIR] [--quick]\n";
      return false;
    }
  }
  return true;
}

std::string output_path(const std::string& directory, const std::string& file) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);  // check_output_path names a failure
  const std::string path = directory + "/" + file;
  check_output_path(path, "--out");
  return path;
}

}  // namespace contactqp::bench
