#include "contactqp/timer.hpp"

namespace contactqp {

void Timings::add(const std::string& phase, double seconds) {
  for (auto& entry : phases_) {
    if (entry.first == phase) {
      entry.second += seconds;
      return;
    }
  }
  phases_.emplace_back(phase, seconds);
}

double Timings::get(const std::string& phase) const {
  for (const auto& entry : phases_)
    if (entry.first == phase) return entry.second;
  return 0.0;
}

bool Timings::has(const std::string& phase) const {
  for (const auto& entry : phases_)
    if (entry.first == phase) return true;
  return false;
}

void Timings::merge(const Timings& other) {
  for (const auto& entry : other.phases_) add(entry.first, entry.second);
}

}  // namespace contactqp
