#include "qp/words.hpp"

#include <algorithm>
#include <cctype>

namespace contactqp::detail {
namespace {

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

}  // namespace

std::string nearest(const std::string& word, const std::vector<std::string>& valid) {
  std::string best;
  size_t best_distance = std::max<size_t>(3, word.size() / 2) + 1;
  const std::string lower_word = lower(word);
  for (const std::string& candidate : valid) {
    const std::string lower_candidate = lower(candidate);
    size_t distance = edit_distance(lower_word, lower_candidate);
    // A prefix ("tol" for "tolerance") is as good a hint as a typo.
    if (lower_candidate.rfind(lower_word, 0) == 0 || lower_word.rfind(lower_candidate, 0) == 0)
      distance = std::min<size_t>(distance, 1);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

}  // namespace contactqp::detail

namespace contactqp {

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

}  // namespace contactqp
