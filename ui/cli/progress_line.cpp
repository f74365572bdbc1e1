#include "ui/cli/progress_line.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace plumb::cli {
namespace {

constexpr double kQuietSeconds = 1.0;
constexpr double kTerminalIntervalSeconds = 0.1;
constexpr double kLogIntervalSeconds = 5.0;
constexpr int kBarWidth = 24;

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Built in place: GCC 12 warns (-Wrestrict, a false positive in its string concatenation) on
// "[" + std::string(...) + ...
std::string bar(double fraction) {
  const auto filled = static_cast<std::size_t>(std::clamp(fraction, 0.0, 1.0) * kBarWidth);
  std::string text(kBarWidth + 2, ' ');
  text.front() = '[';
  text.back() = ']';
  std::fill_n(text.begin() + 1, filled, '#');
  return text;
}

}  // namespace

ProgressLine::ProgressLine(std::string label)
    : label_(std::move(label)),
      terminal_(::isatty(STDERR_FILENO) == 1),
      start_(Clock::now()),
      last_print_(start_),
      phase_start_(start_) {}

ProgressLine::~ProgressLine() {
  finish();
}

bool ProgressLine::due() {
  const Clock::time_point now = Clock::now();
  if (secondsBetween(start_, now) < kQuietSeconds) return false;
  if (shown_ && secondsBetween(last_print_, now) < (terminal_ ? kTerminalIntervalSeconds : kLogIntervalSeconds)) {
    return false;
  }
  last_print_ = now;
  return true;
}

void ProgressLine::show(const std::string& text) {
  shown_ = true;
  if (terminal_) {
    std::fprintf(stderr, "\r\033[K%s: %s", label_.c_str(), text.c_str());
  } else {
    std::fprintf(stderr, "%s: %s\n", label_.c_str(), text.c_str());
  }
  std::fflush(stderr);
}

void ProgressLine::update(double fraction) {
  if (!due()) return;
  const double elapsed = secondsBetween(start_, Clock::now());
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  char text[128];
  std::snprintf(text, sizeof text, "%s %3.0f%%, %.0f s left", terminal_ ? bar(fraction).c_str() : "", 100.0 * fraction,
                left);
  show(text);
}

void ProgressLine::update(std::string_view phase, std::uint64_t done, std::uint64_t total) {
  if (phase != phase_) {
    phase_ = phase;
    phase_start_ = Clock::now();
  }
  if (!due()) return;
  const double elapsed = std::max(secondsBetween(phase_start_, Clock::now()), 1e-9);
  const double rate = static_cast<double>(done) / elapsed;
  char text[160];
  if (total > 0) {
    const double fraction = static_cast<double>(done) / static_cast<double>(total);
    const double left = rate > 0.0 ? static_cast<double>(total - std::min(done, total)) / rate : 0.0;
    std::snprintf(text, sizeof text, "%s %s %3.0f%%, %.2f M points/s, %.0f s left", phase_.c_str(),
                  terminal_ ? bar(fraction).c_str() : "", 100.0 * fraction, rate / 1e6, left);
  } else {
    std::snprintf(text, sizeof text, "%s %.1f M points, %.2f M points/s", phase_.c_str(),
                  static_cast<double>(done) / 1e6, rate / 1e6);
  }
  show(text);
}

void ProgressLine::finish() {
  if (shown_ && terminal_) std::fprintf(stderr, "\r\033[K");
  shown_ = false;
}

}  // namespace plumb::cli
