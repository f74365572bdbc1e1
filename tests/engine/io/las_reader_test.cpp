// LAS reader tests on small LAS files built byte by byte (buildLas) in a temporary directory.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/io/point_reader.h"

namespace plumb::io {
namespace {

namespace fs = std::filesystem;

// Standard record sizes and colour offsets of point formats 0 to 10 (LAS 1.4 R15); 0: no colour.
constexpr std::array<std::size_t, 11> kRecordBytes{20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
constexpr std::array<std::size_t, 11> kColourAt{0, 0, 20, 28, 0, 28, 0, 30, 30, 0, 30};
constexpr std::array<std::size_t, 5> kHeaderBytes{227, 227, 227, 235, 375};  // by minor version

struct LasPoint {
  std::int32_t x, y, z;
  std::uint16_t intensity;
  std::array<std::uint16_t, 3> rgb;
};

struct Vlr {
  std::string user_id;
  std::size_t payload_bytes;
  std::uint16_t record_id = 0;
};

// Everything buildLas writes; the defaults make a valid LAS 1.2 format 0 file.
struct LasSpec {
  std::uint8_t minor = 2;
  std::uint8_t format = 0;                     // the byte as written: LAZ bits and bad formats allowed
  std::optional<std::uint16_t> header_size;    // default: the version's size
  std::size_t extra_bytes = 0;                 // appended to every record, counted in the record length
  std::optional<std::uint16_t> record_length;  // default: standard size + extra_bytes
  std::vector<Vlr> vlrs;
  std::vector<std::size_t> evlr_payload_bytes;  // 1.4: EVLRs after the point data
  std::optional<std::uint32_t> point_offset;    // default: after the header and the VLRs
  std::optional<std::uint32_t> legacy_count;    // default: the point count (0 for formats 6 to 10)
  std::optional<std::uint64_t> count64;         // 1.4; default: the point count
  std::array<double, 3> scale{0.001, 0.001, 0.001};
  std::array<double, 3> offset{512000.0, 5403000.0, 250.0};
  std::array<double, 3> min{1.0, 2.0, 3.0}, max{4.0, 5.0, 6.0};
  std::vector<LasPoint> points;
};

template <typename T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

// A LAS file image following `spec`: header, VLRs, (LAS 1.0's two-byte start signature),
// point records with every ignored byte set to 0xAB and extra bytes to 0xEE, then EVLRs.
std::string buildLas(const LasSpec& spec) {
  const std::size_t format = spec.format & 0x3F;
  const std::size_t standard = format < kRecordBytes.size() ? kRecordBytes[format] : 20;
  const std::size_t header_size = spec.header_size.value_or(kHeaderBytes[std::min<std::size_t>(spec.minor, 4)]);
  const std::size_t record_length = spec.record_length.value_or(standard + spec.extra_bytes);

  std::string bytes(std::max<std::size_t>(header_size, 375), '\0');
  std::memcpy(bytes.data(), "LASF", 4);
  put<std::uint8_t>(bytes, 24, 1);
  put<std::uint8_t>(bytes, 25, spec.minor);
  put<std::uint16_t>(bytes, 94, static_cast<std::uint16_t>(header_size));
  put<std::uint32_t>(bytes, 100, static_cast<std::uint32_t>(spec.vlrs.size()));
  put<std::uint8_t>(bytes, 104, spec.format);
  put<std::uint16_t>(bytes, 105, static_cast<std::uint16_t>(record_length));
  const auto count = static_cast<std::uint32_t>(spec.points.size());
  put<std::uint32_t>(bytes, 107, spec.legacy_count.value_or(spec.minor >= 4 && format >= 6 ? 0 : count));
  for (std::size_t axis = 0; axis < 3; ++axis) {
    put<double>(bytes, 131 + 8 * axis, spec.scale[axis]);
    put<double>(bytes, 155 + 8 * axis, spec.offset[axis]);
    put<double>(bytes, 179 + 16 * axis, spec.max[axis]);
    put<double>(bytes, 187 + 16 * axis, spec.min[axis]);
  }
  bytes.resize(header_size);

  for (const Vlr& vlr : spec.vlrs) {
    std::string record(54 + vlr.payload_bytes, 'v');
    std::memset(record.data(), 0, 54);
    std::memcpy(record.data() + 2, vlr.user_id.data(), std::min<std::size_t>(vlr.user_id.size(), 16));
    put<std::uint16_t>(record, 18, vlr.record_id);
    put<std::uint16_t>(record, 20, static_cast<std::uint16_t>(vlr.payload_bytes));
    bytes += record;
  }
  if (spec.minor == 0) bytes += "\xDD\xCC";
  const std::size_t point_offset = spec.point_offset.value_or(bytes.size());
  put<std::uint32_t>(bytes, 96, static_cast<std::uint32_t>(point_offset));

  for (const LasPoint& point : spec.points) {
    std::string record(record_length, '\xAB');
    std::memset(record.data() + std::min(standard, record_length), 0xEE,
                record_length - std::min(standard, record_length));
    put(record, 0, point.x);
    put(record, 4, point.y);
    put(record, 8, point.z);
    put(record, 12, point.intensity);
    if (format < kColourAt.size() && kColourAt[format] != 0) {
      for (std::size_t channel = 0; channel < 3; ++channel)
        put(record, kColourAt[format] + 2 * channel, point.rgb[channel]);
    }
    bytes += record;
  }

  if (spec.minor >= 4) {
    put<std::uint64_t>(bytes, 235, spec.evlr_payload_bytes.empty() ? 0 : bytes.size());
    put<std::uint32_t>(bytes, 243, static_cast<std::uint32_t>(spec.evlr_payload_bytes.size()));
    put<std::uint64_t>(bytes, 247, spec.count64.value_or(count));
  }
  for (std::size_t payload : spec.evlr_payload_bytes) {
    std::string record(60 + payload, 'e');
    std::memset(record.data(), 0, 60);
    put<std::uint64_t>(record, 20, payload);
    bytes += record;
  }
  return bytes;
}

// `count` points with distinct coordinates, intensities and colours.
std::vector<LasPoint> samplePoints(int count) {
  std::vector<LasPoint> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({123456 + 1001 * i,
                      -7890 - 17 * i,
                      1500 + i,
                      static_cast<std::uint16_t>(1000 * i + 7),
                      {static_cast<std::uint16_t>(1000 * i + 1), static_cast<std::uint16_t>(65535 - i),
                       static_cast<std::uint16_t>(256 * i)}});
  }
  return points;
}

std::vector<PointRecord> readAll(PointReader& reader, std::size_t max_points = 1000) {
  std::vector<PointRecord> points;
  PointBatch batch;
  while (reader.read(batch, max_points)) points.insert(points.end(), batch.points.begin(), batch.points.end());
  return points;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

class LasReader : public ::testing::Test {
 protected:
  void SetUp() override {
    // Parameterised test names contain '/': keep the directory one level deep.
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_');
    directory_ = fs::temp_directory_path() / ("plumb_las_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string write(const std::string& bytes) {
    const fs::path path = directory_ / "cloud.las";
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path.string();
  }

  // The message of the plumb::Error opening `bytes` throws; a test failure when none is thrown.
  std::string openError(const std::string& bytes) {
    const std::string path = write(bytes);
    try {
      openLas(path);
    } catch (const Error& error) {
      return error.what();
    }
    ADD_FAILURE() << "openLas accepted a malformed file";
    return {};
  }

  fs::path directory_;
};

class LasReaderFormat : public LasReader, public ::testing::WithParamInterface<int> {};

TEST_P(LasReaderFormat, RoundTripsCoordinatesColourAndIntensity) {
  const auto format = static_cast<std::uint8_t>(GetParam());
  LasSpec spec;
  spec.minor = format >= 6 ? 4 : format >= 4 ? 3 : 2;
  spec.format = format;
  spec.points = samplePoints(4);
  const bool has_colour = kColourAt[format] != 0;

  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_EQ(reader->info().format, "LAS 1." + std::to_string(spec.minor) + " point format " + std::to_string(format));
  EXPECT_EQ(reader->info().declared_points, 4u);
  EXPECT_EQ(reader->info().attributes.colour, has_colour);
  EXPECT_TRUE(reader->info().attributes.intensity);
  EXPECT_FALSE(reader->info().attributes.normals);
  EXPECT_TRUE(contains(reader->info().ignored_fields, "classification"));
  EXPECT_EQ(contains(reader->info().ignored_fields, "gps_time"), format != 0 && format != 2);

  const std::vector<PointRecord> points = readAll(*reader);
  ASSERT_EQ(points.size(), 4u);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const LasPoint& written = spec.points[i];
    EXPECT_EQ(points[i].x, written.x * 0.001 + 512000.0);
    EXPECT_EQ(points[i].y, written.y * 0.001 + 5403000.0);
    EXPECT_EQ(points[i].z, written.z * 0.001 + 250.0);
    EXPECT_EQ(points[i].intensity, written.intensity);
    const std::array<std::uint16_t, 3> no_colour{0, 0, 0};
    EXPECT_EQ(points[i].rgb, has_colour ? written.rgb : no_colour);
  }
  // Millimetres: X = 123456 at scale 0.001 and offset 512000 is 512123.456 m.
  EXPECT_NEAR(points[0].x, 512123.456, 1e-9);
  EXPECT_NEAR(points[0].y, 5402992.110, 1e-9);
  EXPECT_NEAR(points[0].z, 251.5, 1e-12);
  EXPECT_EQ(reader->counts().delivered, 4u);
  EXPECT_EQ(reader->counts().non_finite, 0u);
}

INSTANTIATE_TEST_SUITE_P(LasFormats, LasReaderFormat, ::testing::Range(0, 11));

TEST_F(LasReader, ReadsHeadersOfVersions10To14) {
  for (std::size_t minor = 0; minor <= 4; ++minor) {
    SCOPED_TRACE("LAS 1." + std::to_string(minor));
    LasSpec spec;
    spec.minor = static_cast<std::uint8_t>(minor);
    spec.format = 1;
    spec.points = samplePoints(3);
    const std::string bytes = buildLas(spec);
    ASSERT_EQ(bytes.size(), kHeaderBytes[minor] + (minor == 0 ? 2 : 0) + 3 * 28u);
    const auto reader = openLas(write(bytes));
    EXPECT_EQ(reader->info().format, "LAS 1." + std::to_string(minor) + " point format 1");
    const std::vector<PointRecord> points = readAll(*reader);
    ASSERT_EQ(points.size(), 3u);
    EXPECT_EQ(points[2].x, spec.points[2].x * 0.001 + 512000.0);
  }
}

TEST_F(LasReader, ReportsTheDeclaredBounds) {
  LasSpec spec;
  spec.points = samplePoints(1);
  const auto reader = openLas(write(buildLas(spec)));
  ASSERT_TRUE(reader->info().declared_bounds.has_value());
  EXPECT_EQ(reader->info().declared_bounds->min, (std::array<double, 3>{1.0, 2.0, 3.0}));
  EXPECT_EQ(reader->info().declared_bounds->max, (std::array<double, 3>{4.0, 5.0, 6.0}));
}

TEST_F(LasReader, SkipsVlrsOfOddSizesBeforeThePointData) {
  LasSpec spec;
  spec.format = 2;
  spec.vlrs = {{"LASF_Projection", 7}, {"someone", 33}};
  spec.points = samplePoints(3);
  const auto reader = openLas(write(buildLas(spec)));
  const std::vector<PointRecord> points = readAll(*reader);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0].x, spec.points[0].x * 0.001 + 512000.0);
  EXPECT_EQ(points[2].rgb, spec.points[2].rgb);
}

TEST_F(LasReader, StopsAtTheDeclaredCountBeforeEvlrs) {
  LasSpec spec;
  spec.minor = 4;
  spec.format = 6;
  spec.vlrs = {{"someone", 5}};
  spec.evlr_payload_bytes = {30, 91};
  spec.points = samplePoints(3);
  const auto reader = openLas(write(buildLas(spec)));
  const std::vector<PointRecord> points = readAll(*reader);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[2].z, spec.points[2].z * 0.001 + 250.0);
  EXPECT_EQ(reader->counts().delivered, 3u);
}

TEST_F(LasReader, SkipsExtraBytesInLongerRecords) {
  LasSpec spec;
  spec.format = 3;
  spec.extra_bytes = 4;
  spec.points = samplePoints(3);
  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_TRUE(contains(reader->info().ignored_fields, "extra bytes (4 per point)"));
  const std::vector<PointRecord> points = readAll(*reader);
  ASSERT_EQ(points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(points[i].y, spec.points[i].y * 0.001 + 5403000.0);
    EXPECT_EQ(points[i].rgb, spec.points[i].rgb);
    EXPECT_EQ(points[i].intensity, spec.points[i].intensity);
  }
}

TEST_F(LasReader, Uses64BitCountInLas14WhenTheLegacyCountIsZero) {
  LasSpec spec;
  spec.minor = 4;
  spec.format = 1;
  spec.legacy_count = 0;
  spec.points = samplePoints(5);
  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_EQ(reader->info().declared_points, 5u);
  EXPECT_EQ(readAll(*reader).size(), 5u);
}

TEST_F(LasReader, Prefers64BitCountInLas14WhenTheCountsDisagree) {
  LasSpec spec;
  spec.minor = 4;
  spec.format = 7;
  spec.legacy_count = 2;
  spec.points = samplePoints(5);
  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_EQ(reader->info().declared_points, 5u);
  EXPECT_EQ(readAll(*reader).size(), 5u);
}

TEST_F(LasReader, UsesTheLegacyCountInLas14WhenThe64BitCountIsZero) {
  LasSpec spec;
  spec.minor = 4;
  spec.format = 1;
  spec.count64 = 0;
  spec.points = samplePoints(4);
  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_EQ(reader->info().declared_points, 4u);
  EXPECT_EQ(readAll(*reader).size(), 4u);
}

TEST_F(LasReader, IgnoresThe64BitFieldsBeforeLas14) {
  LasSpec spec;
  spec.minor = 3;
  spec.points = samplePoints(2);
  std::string bytes = buildLas(spec);
  // In 1.3 the bytes where 1.4 keeps its 64-bit count are point data; bytes after the last
  // record are not points.
  bytes += std::string(200, '\x7F');
  const auto reader = openLas(write(bytes));
  EXPECT_EQ(reader->info().declared_points, 2u);
  EXPECT_EQ(readAll(*reader).size(), 2u);
}

TEST_F(LasReader, ReadsInBatchesOfAtMostMaxPoints) {
  LasSpec spec;
  spec.format = 3;
  spec.points = samplePoints(5);
  const auto reader = openLas(write(buildLas(spec)));
  PointBatch batch;
  std::vector<std::size_t> sizes;
  std::vector<PointRecord> points;
  while (reader->read(batch, 2)) {
    sizes.push_back(batch.size());
    points.insert(points.end(), batch.points.begin(), batch.points.end());
  }
  EXPECT_EQ(sizes, (std::vector<std::size_t>{2, 2, 1}));
  EXPECT_TRUE(batch.points.empty());
  EXPECT_FALSE(reader->read(batch, 2));
  ASSERT_EQ(points.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(points[i].x, spec.points[i].x * 0.001 + 512000.0);
  EXPECT_EQ(reader->counts().delivered, 5u);
}

TEST_F(LasReader, StreamsManyPointsAcrossReadChunks) {
  // 120000 records of 20 bytes span several of the reader's 1 MiB chunks and two batches.
  LasSpec spec;
  spec.points = samplePoints(120000);
  const auto reader = openLas(write(buildLas(spec)));
  PointBatch batch;
  std::vector<std::size_t> sizes;
  std::size_t index = 0;
  while (reader->read(batch, 100000)) {
    sizes.push_back(batch.size());
    for (const PointRecord& point : batch.points) {
      ASSERT_EQ(point.x, spec.points[index].x * 0.001 + 512000.0) << "point " << index;
      ASSERT_EQ(point.intensity, spec.points[index].intensity) << "point " << index;
      ++index;
    }
  }
  EXPECT_EQ(sizes, (std::vector<std::size_t>{100000, 20000}));
  EXPECT_EQ(reader->counts().delivered, 120000u);
}

TEST_F(LasReader, ZeroPointsIsValidAndYieldsNothing) {
  const auto reader = openLas(write(buildLas(LasSpec{})));
  EXPECT_EQ(reader->info().declared_points, 0u);
  PointBatch batch;
  EXPECT_FALSE(reader->read(batch, 100));
  EXPECT_EQ(batch.size(), 0u);
  EXPECT_EQ(reader->counts().delivered, 0u);
}

TEST_F(LasReader, SkipsAndCountsNonFiniteCoordinates) {
  LasSpec spec;
  spec.scale = {1e308, 0.001, 0.001};
  spec.offset = {0.0, 0.0, 0.0};
  spec.points = {{0, 1, 2, 10, {}}, {1000, 1, 2, 20, {}}, {0, 3, 4, 30, {}}};
  const auto reader = openLas(write(buildLas(spec)));
  const std::vector<PointRecord> points = readAll(*reader);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].intensity, 10);
  EXPECT_EQ(points[1].intensity, 30);
  EXPECT_EQ(reader->counts().non_finite, 1u);
  EXPECT_EQ(reader->counts().delivered, 2u);
}

TEST_F(LasReader, RefusesLazFormatBitsWithoutALaszipVlr) {
  // The compression bits say LAZ, but nothing says how the points are compressed.
  for (const int format : {0x83, 0x43}) {
    SCOPED_TRACE(format);
    LasSpec spec;
    spec.format = static_cast<std::uint8_t>(format);
    spec.points = samplePoints(2);
    const std::string message = openError(buildLas(spec));
    EXPECT_NE(message.find("cloud.las"), std::string::npos) << message;
    EXPECT_NE(message.find("at byte 104"), std::string::npos) << message;
    EXPECT_NE(message.find("marks a LAZ file"), std::string::npos) << message;
    EXPECT_NE(message.find("no laszip VLR"), std::string::npos) << message;
  }
}

TEST_F(LasReader, ALaszipVlrMakesTheFileLazAndIsChecked) {
  // As in LASzip, the VLR (user id "laszip encoded", record id 22204) decides, whatever the
  // format byte's bits: a malformed one (34 bytes, no item) is refused at its payload.
  LasSpec spec;
  spec.format = 3;
  spec.vlrs = {{"LASF_Projection", 11}, {"laszip encoded", 34, 22204}};
  spec.points = samplePoints(2);
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("the laszip VLR has 34 bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 346"), std::string::npos) << message;  // 227 + 54 + 11 + 54

  // With another record id it is not the laszip VLR: a plain LAS file.
  spec.vlrs = {{"LASF_Projection", 11}, {"laszip encoded", 34, 1}};
  const auto reader = openLas(write(buildLas(spec)));
  EXPECT_EQ(reader->info().format, "LAS 1.2 point format 3");
  EXPECT_EQ(readAll(*reader).size(), 2u);
}

TEST_F(LasReader, RejectsAnEmptyFile) {
  const std::string message = openError("");
  EXPECT_NE(message.find("empty"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAWrongSignature) {
  std::string bytes = buildLas(LasSpec{});
  bytes[3] = 'X';
  const std::string message = openError(bytes);
  EXPECT_NE(message.find("LASF"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 0"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsATruncatedHeader) {
  const std::string message = openError(buildLas(LasSpec{}).substr(0, 100));
  EXPECT_NE(message.find("truncated header"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 100"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsATruncated14Header) {
  LasSpec spec;
  spec.minor = 4;
  const std::string message = openError(buildLas(spec).substr(0, 300));
  EXPECT_NE(message.find("truncated header"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsTruncatedPointDataAtOpenTime) {
  LasSpec spec;
  spec.points = samplePoints(5);
  std::string bytes = buildLas(spec);
  bytes.resize(227 + 3 * 20 + 7);  // three whole records and part of the fourth
  const std::string message = openError(bytes);
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 287"), std::string::npos) << message;  // where the fourth record starts
  EXPECT_NE(message.find("only 3 fit"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsPointFormat11) {
  LasSpec spec;
  spec.minor = 4;
  spec.format = 11;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("unknown point data format 11"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 104"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsARecordLengthShorterThanTheFormat) {
  LasSpec spec;
  spec.format = 3;
  spec.record_length = 33;
  spec.points = samplePoints(2);
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("record length 33 is shorter than the 34 bytes"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAPointOffsetPastTheEnd) {
  LasSpec spec;
  spec.point_offset = 100000;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("beyond the end of the file"), std::string::npos) << message;
  EXPECT_NE(message.find("at byte 96"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAPointOffsetInsideTheHeader) {
  LasSpec spec;
  spec.point_offset = 200;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("inside the 227-byte header"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAHeaderSmallerThanTheVersionRequires) {
  LasSpec spec;
  spec.minor = 4;
  spec.header_size = 227;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("header size 227 is smaller than the 375 bytes LAS 1.4 requires"), std::string::npos)
      << message;
}

TEST_F(LasReader, RejectsAnUnknownVersion) {
  LasSpec spec;
  spec.minor = 5;
  spec.header_size = 375;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("unknown LAS version 1.5"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAnAbsurdPointCount) {
  LasSpec spec;
  spec.minor = 4;
  spec.count64 = std::uint64_t{1} << 62;
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("absurd point count"), std::string::npos) << message;
}

TEST_F(LasReader, RejectsAZeroScaleFactor) {
  LasSpec spec;
  spec.scale = {0.01, 0.0, 0.01};
  const std::string message = openError(buildLas(spec));
  EXPECT_NE(message.find("y scale factor"), std::string::npos) << message;
}

}  // namespace
}  // namespace plumb::io
