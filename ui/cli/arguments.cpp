#include "ui/cli/arguments.h"

#include <charconv>
#include <cmath>
#include <filesystem>

#include "engine/core/error.h"

namespace plumb::cli {
namespace {

bool parseFinite(std::string_view text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && stop == end && std::isfinite(value);
}

std::string formatNumber(double value) {
  std::string text = std::to_string(value);
  // std::to_string prints six decimals: drop the trailing zeros for a readable message.
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text;
}

}  // namespace

Eigen::Vector3d parseVector3(const std::string& text, const std::string& option) {
  Eigen::Vector3d result;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    const bool last = i == 2;
    if (last != (comma == std::string::npos) ||
        !parseFinite(std::string_view(text).substr(start, last ? std::string::npos : comma - start), result[i])) {
      throw Error(option + " takes three finite numbers separated by commas, like 512000,5403000,250; got '" + text +
                  "'");
    }
    start = comma + 1;
  }
  return result;
}

CLI::Validator finiteIn(double min, double max) {
  // Built with append: GCC 12 at -O3 warns falsely (-Wrestrict, PR 105651) on "literal" + string.
  std::string range = "[";
  range.append(formatNumber(min)).append(", ").append(formatNumber(max)).append("]");
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        double value = 0.0;
        if (!parseFinite(text, value)) return "'" + text + "' is not a finite number";
        if (value < min || value > max) return "'" + text + "' is outside " + range;
        return {};
      },
      "NUMBER in " + range);
}

std::string withThousands(std::uint64_t value) {
  const std::string digits = std::to_string(value);
  std::string grouped;
  grouped.reserve(digits.size() + digits.size() / 3);
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped.push_back(',');
    grouped.push_back(digits[i]);
  }
  return grouped;
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ignored;
  return std::filesystem::weakly_canonical(std::filesystem::absolute(a, ignored), ignored) ==
         std::filesystem::weakly_canonical(std::filesystem::absolute(b, ignored), ignored);
}

}  // namespace plumb::cli
