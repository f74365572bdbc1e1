#include "cad/number_text.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <charconv>
#include <cmath>

namespace plumb::cad {

void appendNumber(std::string& out, double value) {
  assert(std::isfinite(value) && "appendNumber of a non-finite number: validate the project first");
  // Fixed notation of a double needs at most 309 digits before the point (1.8e308) or 324 after
  // it (the smallest subnormal, 5e-324), plus a sign, a zero and the point.
  std::array<char, 352> text;
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value, std::chars_format::fixed);
  assert(error == std::errc() && "appendNumber: the buffer holds any double");
  out.append(text.data(), end);
  // A whole number keeps a decimal point, as CAD programs write reals: some readers tell a real
  // from an integer by it.
  if (std::find(text.data(), end, '.') == end) out += ".0";
}

std::string numberText(double value) {
  std::string text;
  appendNumber(text, value);
  return text;
}

}  // namespace plumb::cad
