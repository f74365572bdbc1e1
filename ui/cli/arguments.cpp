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

std::vector<double> parseNumbers(const std::string& text, std::size_t least, std::size_t most,
                                 const std::string& option, const std::string& example) {
  std::vector<double> numbers;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view piece =
        std::string_view(text).substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double value = 0.0;
    if (!parseFinite(piece, value) || numbers.size() == most) {
      numbers.clear();
      break;
    }
    numbers.push_back(value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (numbers.size() < least) {
    const std::string count =
        least == most ? std::to_string(least) : std::to_string(least) + " to " + std::to_string(most);
    throw Error(option + " takes " + count + " finite numbers separated by commas, like " + example + "; got '" + text +
                "'");
  }
  return numbers;
}

Eigen::Vector3d parseVector3(const std::string& text, const std::string& option) {
  const std::vector<double> v = parseNumbers(text, 3, 3, option, "512000,5403000,250");
  return {v[0], v[1], v[2]};
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
