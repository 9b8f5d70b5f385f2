// A list that libraries add their registrations to (cqp_petsc its distributed run and its way of
// holding a QP in parts) and that the generic code reads: added to while the built-in lists run,
// read by every look-up, possibly from several threads, so both go through one mutex and a
// reader works on a copy.
#pragma once

#include <mutex>
#include <utility>
#include <vector>

namespace contactqp::detail {

template <typename T>
class Registrations {
 public:
  void add(T item) {
    std::lock_guard<std::mutex> lock(mutex_);
    items_.push_back(std::move(item));
  }
  std::vector<T> copy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<T> items_;
};

}  // namespace contactqp::detail
