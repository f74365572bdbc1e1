#include "engine/io/text_numbers.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace plumb::io {
namespace {

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const char x = a[i] >= 'A' && a[i] <= 'Z' ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
    if (x != b[i]) return false;
  }
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

}  // namespace

void splitFields(std::string_view line, bool comma, std::vector<std::string_view>& fields) {
  fields.clear();
  if (comma) {
    if (trim(line).empty()) return;
    std::size_t start = 0;
    for (;;) {
      const std::size_t end = line.find(',', start);
      fields.push_back(trim(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
      if (end == std::string_view::npos) break;
      start = end + 1;
    }
    return;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
}

bool parseNumber(std::string_view word, double& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  if (word.empty()) return false;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (end == word.data() + word.size() && (error == std::errc() || error == std::errc::result_out_of_range)) {
    // Out of range: 1e999 is an infinite coordinate to skip, not a malformed file.
    if (error == std::errc::result_out_of_range) value = word.front() == '-' ? -INFINITY : INFINITY;
    return true;
  }
  const bool negative = word.front() == '-';
  const std::string_view magnitude = negative ? word.substr(1) : word;
  if (equalsIgnoringCase(magnitude, "nan")) {
    value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  if (equalsIgnoringCase(magnitude, "inf") || equalsIgnoringCase(magnitude, "infinity")) {
    value = negative ? -INFINITY : INFINITY;
    return true;
  }
  return false;
}

}  // namespace plumb::io
