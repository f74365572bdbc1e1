// ASCII point files: XYZ, TXT, PTS, CSV (and ASC).
//
//   1. Look at the first non-empty lines: a single integer is a PTS point count; a line of
//      names (x, y, z, r, g, b, intensity, nx ...; "//X" as CloudCompare writes it) is a header
//      that says what the columns are; commas anywhere make the file comma-separated.
//   2. Columns: --columns when given, else the header, else by count: 3 x y z; 4 x y z i;
//      6 x y z r g b; 7 x y z i r g b (PTS); 9 x y z r g b nx ny nz; 10 x y z i r g b nx ny nz.
//   3. Stream the lines in batches; every data line must have the same number of values.
//   4. At the end, a PTS count must match the number of points read.
//
// Colour is 8-bit (0..255, widened to 16 bits). Intensity is taken as a 16-bit value, except in
// .pts files, whose intensities run from -2048 to 2047 (Leica's convention) and are shifted and
// scaled to 0..65520.

#include <algorithm>
#include <charconv>
#include <cmath>

#include "engine/io/file_source.h"
#include "engine/io/point_reader.h"
#include "engine/io/text_numbers.h"

namespace plumb::io {
namespace {

enum Column : int { kSkip = -1, kX, kY, kZ, kIntensity, kRed, kGreen, kBlue, kNx, kNy, kNz, kColumnKinds };

int columnNamed(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  while (!name.empty() && name.front() == '/') name.erase(name.begin());  // CloudCompare's "//X"
  static constexpr std::pair<std::string_view, int> kNames[] = {{"x", kX},
                                                                {"y", kY},
                                                                {"z", kZ},
                                                                {"i", kIntensity},
                                                                {"intensity", kIntensity},
                                                                {"scalar_intensity", kIntensity},
                                                                {"r", kRed},
                                                                {"g", kGreen},
                                                                {"b", kBlue},
                                                                {"red", kRed},
                                                                {"green", kGreen},
                                                                {"blue", kBlue},
                                                                {"nx", kNx},
                                                                {"ny", kNy},
                                                                {"nz", kNz},
                                                                {"normal_x", kNx},
                                                                {"normal_y", kNy},
                                                                {"normal_z", kNz},
                                                                {"_", kSkip}};
  for (const auto& [known, column] : kNames) {
    if (known == name) return column;
  }
  return -2;  // unknown
}

std::vector<int> columnsByCount(std::size_t count) {
  switch (count) {
    case 3:
      return {kX, kY, kZ};
    case 4:
      return {kX, kY, kZ, kIntensity};
    case 6:
      return {kX, kY, kZ, kRed, kGreen, kBlue};
    case 7:
      return {kX, kY, kZ, kIntensity, kRed, kGreen, kBlue};
    case 9:
      return {kX, kY, kZ, kRed, kGreen, kBlue, kNx, kNy, kNz};
    case 10:
      return {kX, kY, kZ, kIntensity, kRed, kGreen, kBlue, kNx, kNy, kNz};
    default:
      return {};
  }
}

bool isInteger(std::string_view text, std::uint64_t& value) {
  return !text.empty() &&
         std::from_chars(text.data(), text.data() + text.size(), value).ptr == text.data() + text.size();
}

class AsciiReader final : public PointReader {
 public:
  AsciiReader(const std::string& path, const ReaderOptions& options) : PointReader(path), source_(path) {
    const std::string extension = lowerExtension(path);
    pts_ = extension == ".pts";
    info_.format = "ASCII " + (extension.empty() ? std::string("text") : extension.substr(1));
    readPreamble(options);
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    batch.clear();
    if (pending_) {
      pending_ = false;
      parseLine(batch);
    }
    while (batch.size() < max_points && source_.readLine(line_)) parseLine(batch);
    if (batch.points.empty() && !checked_end_) checkEnd();
    return !batch.points.empty();
  }

 private:
  // Reads up to the first data line (kept in line_ as pending) and settles the columns.
  void readPreamble(const ReaderOptions& options) {
    std::vector<int> header_columns;
    while (source_.readLine(line_)) {
      if (line_.find_first_not_of(" \t,") == std::string::npos) continue;
      comma_ = line_.find(',') != std::string::npos;
      splitFields(line_, comma_, fields_);
      std::uint64_t count = 0;
      if (fields_.size() == 1 && !info_.declared_points && header_columns.empty() && isInteger(fields_[0], count)) {
        info_.declared_points = count;  // a PTS count line
        continue;
      }
      double number = 0.0;
      if (!parseNumber(fields_[0], number)) {
        if (!header_columns.empty()) throw source_.errorAtLine("a second header line");
        for (std::string_view field : fields_) {
          const int column = columnNamed(std::string(field));
          if (column == -2) info_.ignored_fields.emplace_back(field);
          header_columns.push_back(column < 0 ? kSkip : column);
        }
        continue;
      }
      pending_ = true;
      break;
    }
    if (!pending_) {
      columns_ = {kX, kY, kZ};
      checkColumns();
      return;  // no data at all: an empty cloud
    }
    if (!options.columns.empty()) {
      std::vector<std::string_view> names;
      splitFields(options.columns, /*comma=*/true, names);
      for (std::string_view name : names) {
        const int column = columnNamed(std::string(name));
        if (column == -2) {
          throw Error("--columns: unknown column '" + std::string(name) +
                      "'; use x y z, i, r g b, nx ny nz or _ to skip a column");
        }
        columns_.push_back(column);
      }
    } else if (!header_columns.empty()) {
      columns_ = header_columns;
    } else {
      columns_ = columnsByCount(fields_.size());
      if (columns_.empty()) {
        throw source_.errorAtLine(std::to_string(fields_.size()) +
                                  " columns: say what they are with --columns, e.g. --columns x,y,z,i,r,g,b");
      }
    }
    if (columns_.size() != fields_.size()) {
      throw source_.errorAtLine("the line has " + std::to_string(fields_.size()) + " values but " +
                                std::to_string(columns_.size()) + " columns are named");
    }
    checkColumns();
  }

  void checkColumns() {
    std::array<int, kColumnKinds> seen{};
    for (int column : columns_) {
      if (column >= 0 && ++seen[static_cast<std::size_t>(column)] > 1) {
        throw Error("'" + path_ + "': a column is named twice");
      }
    }
    if (!seen[kX] || !seen[kY] || !seen[kZ]) throw Error("'" + path_ + "': the columns lack x, y or z");
    info_.attributes.intensity = seen[kIntensity];
    info_.attributes.colour = seen[kRed] && seen[kGreen] && seen[kBlue];
    info_.attributes.normals = seen[kNx] && seen[kNy] && seen[kNz];
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      if (columns_[i] >= kRed && columns_[i] <= kBlue)
        colour_field_[static_cast<std::size_t>(columns_[i] - kRed)] = static_cast<int>(i);
    }
  }

  void parseLine(PointBatch& batch) {
    splitFields(line_, comma_, fields_);
    if (fields_.empty()) return;
    if (fields_.size() != columns_.size()) {
      throw source_.errorAtLine("expected " + std::to_string(columns_.size()) + " values, found " +
                                std::to_string(fields_.size()));
    }
    std::array<double, kColumnKinds> value{};
    for (std::size_t i = 0; i < fields_.size(); ++i) {
      if (columns_[i] == kSkip) continue;
      if (!parseNumber(fields_[i], value[static_cast<std::size_t>(columns_[i])])) {
        throw source_.errorAtLine("'" + std::string(fields_[i]) + "' in column " + std::to_string(i + 1) +
                                  " is not a number");
      }
    }
    PointRecord point{value[kX], value[kY], value[kZ], {0, 0, 0}, 0};
    // The attributes of a point that will be skipped (NaN position) are not checked.
    if (info_.attributes.colour && point.hasFinitePosition()) {
      for (std::size_t c = 0; c < 3; ++c) {
        const double channel = value[kRed + c];
        if (!(channel >= 0.0 && channel <= 255.0)) {
          throw source_.errorAtLine("colour value '" +
                                    std::string(fields_[static_cast<std::size_t>(colour_field_[c])]) +
                                    "' is outside 0..255");
        }
        point.rgb[c] = widenColour(static_cast<std::uint8_t>(std::lround(channel)));
      }
    }
    if (info_.attributes.intensity) {
      const double raw = value[kIntensity];
      const double scaled = pts_ ? (raw + 2048.0) * 16.0 : raw;
      point.intensity = intensityFrom(scaled);
    }
    deliver(batch, point,
            {static_cast<float>(value[kNx]), static_cast<float>(value[kNy]), static_cast<float>(value[kNz])});
  }

  void checkEnd() {
    checked_end_ = true;
    const std::uint64_t lines = counts_.delivered + counts_.non_finite;
    if (info_.declared_points && *info_.declared_points != lines) {
      throw Error("'" + path_ + "': the count line declares " + std::to_string(*info_.declared_points) +
                  " points but the file holds " + std::to_string(lines));
    }
  }

  FileSource source_;
  bool pts_ = false;
  bool comma_ = false;
  bool pending_ = false;
  bool checked_end_ = false;
  std::vector<int> columns_;
  std::array<int, 3> colour_field_{};  // the field index of red, green and blue
  std::string line_;
  std::vector<std::string_view> fields_;
};

}  // namespace

std::unique_ptr<PointReader> openAscii(const std::string& path, const ReaderOptions& options) {
  return std::make_unique<AsciiReader>(path, options);
}

}  // namespace plumb::io
