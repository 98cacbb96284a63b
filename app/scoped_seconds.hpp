// Adds the wall seconds of a scope to a sum (the summary's timings).
#pragma once

#include <chrono>

namespace xshell {

class ScopedSeconds {
 public:
  // seconds: the sum, or null (nothing is added).
  explicit ScopedSeconds(double* seconds)
      : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopedSeconds() {
    if (seconds_) *seconds_ += elapsed();
  }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  double* seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace xshell
