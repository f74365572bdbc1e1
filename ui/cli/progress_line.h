#pragma once
// Progress of a long command on stderr: a live bar with rate and time left on a terminal, a
// plain line every few seconds otherwise (logs, CI), nothing for commands that finish quickly.
// Single-threaded: call update() from one thread.

#include <chrono>
#include <string>

namespace plumb::cli {

class ProgressLine {
 public:
  // `label` starts each line, e.g. "simulate".
  explicit ProgressLine(std::string label);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // fraction in [0, 1].
  void update(double fraction);
  // Clears the live bar so the command's summary starts on a clean line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  bool terminal_;
  bool shown_ = false;
  Clock::time_point start_;
  Clock::time_point last_print_;
};

}  // namespace plumb::cli
