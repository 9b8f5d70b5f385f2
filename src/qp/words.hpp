// The words of the error messages that refuse a name (a misspelled scene key, a boundary, a
// backend): the list of valid ones and the "did you mean".
#pragma once

#include <string>
#include <vector>

#include "contactqp/errors.hpp"  // join(): "a, b, c"

namespace contactqp::detail {

// The valid word closest to `word` by edit distance (case-insensitive; a prefix counts as one
// edit), or "" when none is close.
std::string nearest(const std::string& word, const std::vector<std::string>& valid);

}  // namespace contactqp::detail
