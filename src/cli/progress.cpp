#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace contactqp::cli {
namespace {

// Shorter runs finish before a line would help; a redraw four times a second reads as live.
constexpr std::chrono::milliseconds kFirstShown{2000}, kRedraw{250};

}  // namespace

ProgressLine::ProgressLine(bool enabled) {
  if (enabled && isatty(STDERR_FILENO)) thread_ = std::thread([this] { run(); });
}

ProgressLine::~ProgressLine() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (shown_) std::fprintf(stderr, "\r\033[K");  // erase the line
  std::fflush(stderr);
}

void ProgressLine::set(const std::string& phase, double fraction) {
  std::lock_guard<std::mutex> lock(mutex_);
  phase_ = phase;
  fraction_ = fraction;
}

void ProgressLine::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_until(lock, start_ + kFirstShown, [this] { return done_; })) return;
  while (!done_) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (fraction_ >= 0)
      std::fprintf(stderr, "\rcontactqp: %s %3.0f%%, %.0f s\033[K", phase_.c_str(), 100 * fraction_, elapsed);
    else
      std::fprintf(stderr, "\rcontactqp: %s, %.0f s\033[K", phase_.c_str(), elapsed);
    std::fflush(stderr);
    shown_ = true;
    wake_.wait_for(lock, kRedraw, [this] { return done_; });
  }
}

}  // namespace contactqp::cli
