// The progress line of a long run: on stderr, rewritten in place, only when stderr is a
// terminal (a log file or a pipe gets nothing) and the run has taken more than two seconds.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace contactqp::cli {

class ProgressLine {
 public:
  // Shows nothing when `enabled` is false (--quiet) or stderr is not a terminal.
  explicit ProgressLine(bool enabled);
  // Erases the line (the summary then starts on a clean line).
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // The phase now running, e.g. "mesh", and how much of it is done when known (0–1; < 0: unknown).
  void set(const std::string& phase, double fraction = -1);

 private:
  void run();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string phase_ = "start";
  double fraction_ = -1;
  bool done_ = false, shown_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::thread thread_;
};

}  // namespace contactqp::cli
