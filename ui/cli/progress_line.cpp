#include "ui/cli/progress_line.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace plumb::cli {
namespace {

// A bar appears only after this long, so quick commands print nothing but their result.
constexpr double kQuietSeconds = 1.0;
constexpr double kTerminalIntervalSeconds = 0.1;
constexpr double kLogIntervalSeconds = 5.0;
constexpr int kBarWidth = 30;

}  // namespace

ProgressLine::ProgressLine(std::string label)
    : label_(std::move(label)), terminal_(::isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_print_(start_) {}

ProgressLine::~ProgressLine() {
  finish();
}

void ProgressLine::update(double fraction) {
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since_print = std::chrono::duration<double>(now - last_print_).count();
  if (elapsed < kQuietSeconds || since_print < (terminal_ ? kTerminalIntervalSeconds : kLogIntervalSeconds)) return;
  last_print_ = now;
  shown_ = true;
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const int percent = static_cast<int>(std::lround(100.0 * fraction));
  if (terminal_) {
    const int filled = static_cast<int>(kBarWidth * fraction);
    std::fprintf(stderr, "\r%s [%-*s] %3d%%  %.0f s left ", label_.c_str(), kBarWidth,
                 std::string(static_cast<std::size_t>(filled), '#').c_str(), percent, left);
  } else {
    std::fprintf(stderr, "%s: %d%% after %.0f s, about %.0f s left\n", label_.c_str(), percent, elapsed, left);
  }
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (shown_ && terminal_) std::fprintf(stderr, "\r\033[K");
  shown_ = false;
}

}  // namespace plumb::cli
