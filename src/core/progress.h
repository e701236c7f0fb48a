#pragma once
// A one-line progress bar on stderr: count, rate, ETA. Redraws at most 10 times a second; when
// stderr is not a terminal it prints a plain line every 10% instead, so CI logs stay readable.
#include <chrono>
#include <cstdint>
#include <string>

namespace inet {

class ProgressBar {
 public:
  ProgressBar(int64_t total, std::string unit, bool enabled = true);
  /// Sets the number of finished items (monotonic) and redraws if due.
  void update(int64_t done);
  /// Draws the final state and ends the line.
  void finish();

 private:
  void draw(bool final);
  int64_t total_;
  int64_t done_ = 0;
  std::string unit_;
  bool enabled_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

/// Formats seconds as H:MM:SS or M:SS.
std::string formatDuration(double seconds);

}  // namespace inet
