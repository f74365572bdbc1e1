#pragma once
// Streaming point-cloud readers: PLY, LAS and LAZ, PCD, E57 and ASCII (XYZ, TXT, PTS, CSV).
//
// A reader delivers points in batches of bounded size and never holds the whole file in memory
// (except PCD binary_compressed, whose single LZF block must be decompressed whole).
// Points with NaN or infinite coordinates are skipped and counted (ReadCounts), never passed on.
// Anything malformed (truncated data, counts that disagree with the data, unknown types) throws
// plumb::Error naming the file and the byte offset or line.
//
// Not thread-safe: one thread reads one reader.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace plumb::io {

// One point: world coordinates (any scale and offset of the file applied), 16-bit colour and
// intensity (8-bit sources are scaled by 257 so that 255 becomes 65535; 0 where absent).
struct PointRecord {
  double x, y, z;
  std::array<std::uint16_t, 3> rgb;
  std::uint16_t intensity;
  std::uint16_t scan = 0;  // the scan of the file it belongs to (CloudInfo::scans); 0 where a file is one scan

  bool hasFinitePosition() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

struct PointBatch {
  std::vector<PointRecord> points;
  // One normal per point when the file has normals (CloudInfo::attributes.normals), else empty.
  std::vector<std::array<float, 3>> normals;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  void clear() {
    points.clear();
    normals.clear();
  }
};

struct PointAttributes {
  bool colour = false;
  bool intensity = false;
  bool normals = false;
};

struct Bounds {
  std::array<double, 3> min, max;
};

// What the header says, known once the reader is open.
struct CloudInfo {
  std::string format;                            // e.g. "PLY binary_little_endian", "LAS 1.4 point format 6"
  std::optional<std::uint64_t> declared_points;  // the count the header states, if it states one
  std::optional<Bounds> declared_bounds;         // the bounds the header states (LAS), unchecked
  PointAttributes attributes;
  // Properties or fields present in the file but not kept, e.g. "label (int)".
  std::vector<std::string> ignored_fields;
  // The names of the scans the file holds (E57: one per data3D), in the order of
  // PointRecord::scan; empty for formats that hold one scan.
  std::vector<std::string> scans;
};

// What reading found, growing as batches are read.
struct ReadCounts {
  std::uint64_t delivered = 0;  // points handed out
  // Skipped: no valid position. A NaN or infinite coordinate (organized PCD's invalid pixels
  // too), or a point the file marks invalid (E57's invalid states).
  std::uint64_t non_finite = 0;
};

class PointReader {
 public:
  virtual ~PointReader() = default;

  const CloudInfo& info() const { return info_; }
  const ReadCounts& counts() const { return counts_; }
  const std::string& path() const { return path_; }

  // Clears `batch` and fills it with up to `max_points` (>= 1) points. Returns false when the file is
  // exhausted and the batch is empty. Throws plumb::Error on malformed content; after the last
  // point it also checks that the data matched the header (no missing and no surplus records).
  virtual bool read(PointBatch& batch, std::size_t max_points) = 0;

 protected:
  explicit PointReader(std::string path) : path_(std::move(path)) {}

  // Hands one decoded point to `batch` (with its normal when the file has normals), or counts it
  // as skipped when a coordinate is NaN or infinite. Every reader ends a point here, so nothing
  // is dropped without being counted.
  void deliver(PointBatch& batch, const PointRecord& point, const std::array<float, 3>& normal = {}) {
    if (!point.hasFinitePosition()) {
      ++counts_.non_finite;
      return;
    }
    batch.points.push_back(point);
    if (info_.attributes.normals) batch.normals.push_back(normal);
    ++counts_.delivered;
  }

  std::string path_;
  CloudInfo info_;
  ReadCounts counts_;
};

struct ReaderOptions {
  // ASCII formats only: the meaning of each column, e.g. "x,y,z,i,r,g,b" (names: x y z, i for
  // intensity, r g b, nx ny nz, and _ for a column to ignore). Empty: detected from the header
  // line or the column count.
  std::string columns;
};

// The extension of `path` in lower case, with its dot: "scan.LAS" -> ".las"; "" without one.
std::string lowerExtension(const std::string& path);

// Opens `path` with the reader its content (and, for ASCII, its extension) calls for.
// Throws plumb::Error for an unknown or unsupported format (LAZ of the layered coder, LAS 1.4
// point formats 6 to 10, is recognised and refused).
std::unique_ptr<PointReader> openPointCloud(const std::string& path, const ReaderOptions& options = {});

// The readers, for callers that know the format.
std::unique_ptr<PointReader> openPly(const std::string& path);
std::unique_ptr<PointReader> openLas(const std::string& path);  // LAS and LAZ
std::unique_ptr<PointReader> openPcd(const std::string& path);
std::unique_ptr<PointReader> openAscii(const std::string& path, const ReaderOptions& options);
std::unique_ptr<PointReader> openE57(const std::string& path);

// 8-bit colour to the 16-bit scale of PointRecord.
constexpr std::uint16_t widenColour(std::uint8_t value) {
  return static_cast<std::uint16_t>(value * 257);
}

// std::round(value) for a finite value, without the library call where it is a whole number
// already (every integer property of a binary file).
inline double roundedToWhole(double value) {
  if (std::abs(value) < 0x1p52) {
    const double whole = static_cast<double>(static_cast<std::int64_t>(value));
    if (whole == value) return value;
  }
  return std::round(value);
}

// An intensity value of a file, taken as 16-bit: rounded and clamped to 0..65535; 0 when NaN.
inline std::uint16_t intensityFrom(double value) {
  if (!std::isfinite(value)) return 0;
  return static_cast<std::uint16_t>(std::clamp(roundedToWhole(value), 0.0, 65535.0));
}

}  // namespace plumb::io
