// Wall-clock timing of named phases ("mesh", "assemble", "factorize", "solve", ...), in seconds.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace contactqp {

// Seconds per named phase, in the order the phases were first recorded. Adding to an
// existing phase accumulates, so a phase run twice reports its total.
class Timings {
 public:
  void add(const std::string& phase, double seconds);
  double get(const std::string& phase) const;  // 0 for a phase never recorded
  bool has(const std::string& phase) const;
  void merge(const Timings& other);  // adds every phase of `other`
  const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }

 private:
  std::vector<std::pair<std::string, double>> phases_;
};

// Measures the wall time since construction or the last restart().
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace contactqp
