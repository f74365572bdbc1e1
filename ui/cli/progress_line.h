#pragma once
// Progress of a long command on stderr: a live bar with rate and time left on a terminal, a
// plain line every few seconds otherwise (logs, CI), nothing for commands that finish within a
// second. Single-threaded: calls must not overlap.

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace plumb::cli {

class ProgressLine {
 public:
  // `label` starts each line, e.g. "simulate".
  explicit ProgressLine(std::string label);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // A single phase: fraction in [0, 1].
  void update(double fraction);
  // A named phase counting points: `done` of `total` (total 0 when not known yet). Shows the
  // phase, the points per second and, when the total is known, the time the phase has left.
  void update(std::string_view phase, std::uint64_t done, std::uint64_t total);
  // Clears the live bar so the command's summary starts on a clean line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool due();
  void show(const std::string& text);

  std::string label_;
  bool terminal_;
  bool shown_ = false;
  Clock::time_point start_;
  Clock::time_point last_print_;
  std::string phase_;
  Clock::time_point phase_start_;
};

}  // namespace plumb::cli
