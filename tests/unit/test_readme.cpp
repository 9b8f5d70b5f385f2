// The README's test command is the one CI runs: keep them the same string.
#include <catch2/catch.hpp>
#include <sstream>

#include "test_support.hpp"

using namespace contactqp::testing;

TEST_CASE("the README shows the exact command .ci/run executes", "[unit][docs]") {
  std::istringstream ci(read_text(source_path(".ci/run")));
  std::string line, command;
  while (std::getline(ci, line))
    if (!line.empty() && line[0] != '#' && line.rfind("set ", 0) != 0 && line.rfind("cd ", 0) != 0) command = line;
  REQUIRE_FALSE(command.empty());
  CHECK(read_text(source_path("README.md")).find("    " + command + "\n") != std::string::npos);
}

TEST_CASE("the README is a door, not a book: at most 15 KB", "[unit][docs]") {
  // The studies live in docs/ (tools/check_links.py checks that the README's links reach them).
  CHECK(read_text(source_path("README.md")).size() <= 15u * 1024u);
}
