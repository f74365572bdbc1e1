#pragma once
// Splitting and number parsing for the text formats (ASCII PLY, XYZ/TXT/PTS/CSV, ASCII PCD).

#include <string_view>
#include <vector>

namespace plumb::io {

// The words of `line` separated by runs of spaces and tabs, or, when `comma` is set, by single
// commas (surrounding spaces trimmed; empty fields kept so that column counts stay right).
void splitFields(std::string_view line, bool comma, std::vector<std::string_view>& fields);

// A decimal number as text files write it: leading '+', "nan", "-nan", "inf" in any case.
// False when `word` is not entirely a number.
bool parseNumber(std::string_view word, double& value);

}  // namespace plumb::io
