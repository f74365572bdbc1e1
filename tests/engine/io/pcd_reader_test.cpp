// Tests of the PCD reader and the LZF decompressor on small hand-made files:
//
//   1. LZF: literal runs, back references (overlapping, long, far), malformed blocks, random
//      input (for the sanitizers), and round trips through a tiny compressor written here.
//   2. PCD: the same cloud as ascii, binary and binary_compressed; colour, intensity, normals,
//      double coordinates, an organized cloud with NaN pixels, batching, header variants.
//   3. PCD errors: one malformed file per error the reader reports.

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <random>

#include "engine/core/error.h"
#include "engine/io/lzf.h"
#include "engine/io/point_reader.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

static_assert(std::endian::native == std::endian::little, "the test files are built in host byte order");

std::vector<std::byte> bytes(std::string_view text) {
  const auto view = std::as_bytes(std::span(text.data(), text.size()));
  return {view.begin(), view.end()};
}

// LZF of `text` by greedy longest-match search (slow, for small test data only).
std::string lzfCompress(std::string_view in) {
  std::string out;
  std::string literal;
  const auto flush = [&] {
    for (std::size_t at = 0; at < literal.size(); at += 32) {
      const std::size_t run = std::min<std::size_t>(32, literal.size() - at);
      out += static_cast<char>(run - 1);
      out += literal.substr(at, run);
    }
    literal.clear();
  };
  std::size_t i = 0;
  while (i < in.size()) {
    std::size_t best = 0;
    std::size_t best_distance = 0;
    for (std::size_t distance = 1; distance <= std::min<std::size_t>(i, 8192); ++distance) {
      std::size_t length = 0;
      while (length < 264 && i + length < in.size() && in[i + length - distance] == in[i + length]) ++length;
      if (length > best) best = length, best_distance = distance;
    }
    if (best < 3) {
      literal += in[i++];
      continue;
    }
    flush();
    const std::size_t offset = best_distance - 1;
    const std::size_t length = best - 2;
    out += static_cast<char>((std::min<std::size_t>(length, 7) << 5) | (offset >> 8));
    if (length >= 7) out += static_cast<char>(length - 7);
    out += static_cast<char>(offset & 0xff);
    i += best;
  }
  flush();
  return out;
}

// Decompresses `in` into an output of `capacity` bytes; nullopt when lzfDecompress refuses.
std::optional<std::string> lzf(std::string_view in, std::size_t capacity, std::size_t* written_out = nullptr) {
  std::vector<std::byte> out(capacity);
  std::size_t written = 0;
  const bool ok = lzfDecompress(bytes(in), out, written);
  if (written_out != nullptr) *written_out = written;
  if (!ok) return std::nullopt;
  return std::string(reinterpret_cast<const char*>(out.data()), written);
}

TEST(Lzf, LiteralRuns) {
  EXPECT_EQ(lzf(std::string("\x02"
                            "abc"),
                16),
            "abc");
  const std::string run32(32, 'q');
  EXPECT_EQ(lzf(std::string(1, '\x1f') + run32, 32), run32);
  EXPECT_EQ(lzf("", 0), "");
}

TEST(Lzf, BackReferences) {
  // "abcd", then 3 bytes from 4 back: length code 1 (3 - 2), offset 3 (4 - 1).
  EXPECT_EQ(lzf(std::string("\x03"
                            "abcd"
                            "\x20\x03"),
                16),
            "abcdabc");
  // Overlapping: 8 bytes from 1 back repeat the last byte.
  EXPECT_EQ(lzf(std::string("\x00"
                            "a"
                            "\xc0\x00",
                            4),
                16),
            std::string(9, 'a'));
  // Overlapping with a period of 2: "ab" then 6 bytes from 2 back.
  EXPECT_EQ(lzf(std::string("\x01"
                            "ab"
                            "\x80\x01"),
                16),
            "abababab");
}

TEST(Lzf, LongAndFarMatches) {
  // Length code 7 takes an extra byte: 7 + 255 + 2 = 264 bytes, the longest match.
  std::string expected = "ab";
  while (expected.size() < 266) expected += expected.substr(expected.size() - 2, 2);
  EXPECT_EQ(lzf(std::string("\x01"
                            "ab"
                            "\xe0\xff\x01"),
                300),
            expected);
  // The farthest reference: 8192 bytes back (offset bits all set).
  std::string text;
  std::string block;
  for (int i = 0; i < 8192; ++i) text += static_cast<char>('a' + i % 23);
  for (std::size_t at = 0; at < text.size(); at += 32) block += static_cast<char>(31) + text.substr(at, 32);
  block += std::string("\x3f\xff");  // length code 1 (3 bytes), offset 0x1fff
  EXPECT_EQ(lzf(block, 9000), text + text.substr(0, 3));
}

TEST(Lzf, RejectsMalformedBlocks) {
  std::size_t written = 99;
  EXPECT_EQ(lzf(std::string("\x05"
                            "ab"),
                16, &written),
            std::nullopt)
      << "literal cut short";
  EXPECT_EQ(written, 0u);
  EXPECT_EQ(lzf(std::string(1, '\0'), 16), std::nullopt) << "control byte with no literal";
  EXPECT_EQ(lzf(std::string("\x01"
                            "ab"
                            "\x20"),
                16, &written),
            std::nullopt)
      << "reference without offset byte";
  EXPECT_EQ(written, 2u);
  EXPECT_EQ(lzf(std::string("\x01"
                            "ab"
                            "\xe0"),
                16),
            std::nullopt)
      << "long reference without length byte";
  EXPECT_EQ(lzf(std::string("\x20\x00", 2), 16), std::nullopt) << "reference before any output";
  EXPECT_EQ(lzf(std::string("\x00"
                            "a"
                            "\x20\x01",
                            4),
                16),
            std::nullopt)
      << "offset before the start";
  EXPECT_EQ(lzf(std::string("\x03"
                            "abcd"),
                3),
            std::nullopt)
      << "literal overflows the output";
  EXPECT_EQ(lzf(std::string("\x00"
                            "a"
                            "\xc0\x00",
                            4),
                5, &written),
            std::nullopt)
      << "match overflows the output";
  EXPECT_EQ(written, 1u);
}

TEST(Lzf, RoundTripsThroughTheTestCompressor) {
  std::mt19937 random(7);
  for (const std::size_t size : {1u, 2u, 31u, 32u, 33u, 300u, 5000u}) {
    std::string text;
    for (std::size_t i = 0; i < size; ++i) text += static_cast<char>('a' + random() % (i % 3 == 0 ? 26 : 3));
    const std::string packed = lzfCompress(text);
    EXPECT_EQ(lzf(packed, text.size()), text) << size;
    EXPECT_EQ(lzf(packed, text.size() - 1), std::nullopt) << "one byte short must be refused";
  }
}

TEST(Lzf, RandomInputStaysInBounds) {
  // The sanitizers watch for any read or write outside the spans.
  std::mt19937 random(42);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::byte> in(random() % 48);
    for (auto& b : in) b = static_cast<std::byte>(random());
    std::vector<std::byte> out(random() % 96);
    std::size_t written = 0;
    lzfDecompress(in, out, written);
    ASSERT_LE(written, out.size());
  }
}

// --- PCD -------------------------------------------------------------------------------------

template <typename T>
void put(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

std::string header(std::string_view fields, std::string_view sizes, std::string_view types, std::string_view counts,
                   std::uint64_t width, std::uint64_t height, std::string_view data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + std::string(fields) + "\nSIZE " +
         std::string(sizes) + "\nTYPE " + std::string(types) + "\nCOUNT " + std::string(counts) + "\nWIDTH " +
         std::to_string(width) + "\nHEIGHT " + std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(width * height) + "\nDATA " + std::string(data) + "\n";
}

// binary_compressed data from records of `field_bytes` (array of structures to structure of arrays).
std::string compressedData(const std::string& records, const std::vector<std::size_t>& field_bytes) {
  std::size_t record = 0;
  for (const std::size_t b : field_bytes) record += b;
  const std::size_t points = records.size() / record;
  std::string soa;
  std::size_t offset = 0;
  for (const std::size_t b : field_bytes) {
    for (std::size_t i = 0; i < points; ++i) soa += records.substr(i * record + offset, b);
    offset += b;
  }
  const std::string packed = lzfCompress(soa);
  std::string out;
  put(out, static_cast<std::uint32_t>(packed.size()));
  put(out, static_cast<std::uint32_t>(soa.size()));
  return out + packed;
}

struct Cloud {
  std::vector<PointRecord> points;
  std::vector<std::array<float, 3>> normals;
  CloudInfo info;
  ReadCounts counts;
  std::vector<std::size_t> batch_sizes;
};

Cloud readAll(const std::string& path, std::size_t batch_points = 1000) {
  auto reader = openPcd(path);
  Cloud cloud;
  PointBatch batch;
  while (reader->read(batch, batch_points)) {
    cloud.batch_sizes.push_back(batch.size());
    cloud.points.insert(cloud.points.end(), batch.points.begin(), batch.points.end());
    cloud.normals.insert(cloud.normals.end(), batch.normals.begin(), batch.normals.end());
  }
  cloud.info = reader->info();
  cloud.counts = reader->counts();
  return cloud;
}

std::string text(float value) {
  if (std::isnan(value)) return "nan";
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, static_cast<double>(value)).ptr;
  return std::string(buffer, end);
}

TEST(PcdReader, SameCloudAsAsciiBinaryAndCompressed) {
  struct Row {
    float x, y, z;
    std::uint32_t rgb;
    std::uint16_t intensity;
    float nx, ny, nz, curvature, hist[3];
  };
  const float nan = std::nanf("");
  const std::vector<Row> rows = {{1.5f, -2.25f, 3.0f, 0x00ff8040, 100, 0, 0, 1, 0.5f, {1, 2, 3}},
                                 {nan, nan, nan, 0, 0, 0, 0, 0, 0, {0, 0, 0}},
                                 {-1e5f, 0.125f, 7.75f, 0x00010203, 65535, 1, 0, 0, 0.25f, {4, 5, 6}},
                                 {4.0f, 4.0f, nan, 0x00ffffff, 7, 0, 1, 0, 0, {7, 8, 9}},
                                 {0.0f, 1.0f, -8.5f, 0x00000000, 0, 0, -1, 0, 1, {0, 0, 0}}};
  const std::string fields = "x y z rgb intensity normal_x normal_y normal_z curvature hist";
  const std::string sizes = "4 4 4 4 2 4 4 4 4 4";
  const std::string types = "F F F F U F F F F F";
  const std::string counts = "1 1 1 1 1 1 1 1 1 3";
  std::string ascii = header(fields, sizes, types, counts, rows.size(), 1, "ascii");
  std::string records;
  for (const Row& row : rows) {
    ascii += text(row.x) + " " + text(row.y) + " " + text(row.z) + " " + text(std::bit_cast<float>(row.rgb)) + " " +
             std::to_string(row.intensity);
    for (const float v : {row.nx, row.ny, row.nz, row.curvature, row.hist[0], row.hist[1], row.hist[2]}) {
      ascii += ' ';  // appended apart: GCC 12 -O3 warns (-Wrestrict) on " " + std::string
      ascii += text(v);
    }
    ascii += "\n";
    for (const float v : {row.x, row.y, row.z}) put(records, v);
    put(records, row.rgb);
    put(records, row.intensity);
    for (const float v : {row.nx, row.ny, row.nz, row.curvature, row.hist[0], row.hist[1], row.hist[2]})
      put(records, v);
  }
  test::TempDirectory dir;
  const Cloud a = readAll(dir.write("a.pcd", ascii));
  const Cloud b = readAll(dir.write("b.pcd", header(fields, sizes, types, counts, rows.size(), 1, "binary") + records));
  const Cloud c = readAll(dir.write("c.pcd", header(fields, sizes, types, counts, rows.size(), 1, "binary_compressed") +
                                                 compressedData(records, {4, 4, 4, 4, 2, 4, 4, 4, 4, 12})));
  EXPECT_EQ(a.info.format, "PCD 0.7 ascii");
  EXPECT_EQ(b.info.format, "PCD 0.7 binary");
  EXPECT_EQ(c.info.format, "PCD 0.7 binary_compressed");
  for (const Cloud* cloud : {&a, &b, &c}) {
    SCOPED_TRACE(cloud->info.format);
    EXPECT_EQ(cloud->info.declared_points, 5u);
    EXPECT_TRUE(cloud->info.attributes.colour && cloud->info.attributes.intensity && cloud->info.attributes.normals);
    EXPECT_EQ(cloud->info.ignored_fields, (std::vector<std::string>{"curvature (F4)", "hist (F4 x3)"}));
    EXPECT_EQ(cloud->counts.delivered, 3u);
    EXPECT_EQ(cloud->counts.non_finite, 2u);
    ASSERT_EQ(cloud->points.size(), 3u);
    ASSERT_EQ(cloud->normals.size(), 3u);
    std::size_t p = 0;
    for (const Row& row : rows) {
      if (std::isnan(row.x) || std::isnan(row.z)) continue;
      const PointRecord& point = cloud->points[p];
      EXPECT_EQ(point.x, row.x);
      EXPECT_EQ(point.y, row.y);
      EXPECT_EQ(point.z, row.z);
      EXPECT_EQ(point.rgb[0], ((row.rgb >> 16) & 0xff) * 257);
      EXPECT_EQ(point.rgb[1], ((row.rgb >> 8) & 0xff) * 257);
      EXPECT_EQ(point.rgb[2], (row.rgb & 0xff) * 257);
      EXPECT_EQ(point.intensity, row.intensity);
      EXPECT_EQ(cloud->normals[p], (std::array<float, 3>{row.nx, row.ny, row.nz}));
      ++p;
    }
  }
}

TEST(PcdReader, PackedRgbaAndIntegerRgb) {
  test::TempDirectory dir;
  std::string records;
  for (const float v : {1.0f, 2.0f, 3.0f}) put(records, v);
  put(records, std::uint32_t{0x80112233});
  const Cloud rgba =
      readAll(dir.write("rgba.pcd", header("x y z rgba", "4 4 4 4", "F F F U", "1 1 1 1", 1, 1, "binary") + records));
  ASSERT_EQ(rgba.points.size(), 1u);
  EXPECT_EQ(rgba.points[0].rgb, (std::array<std::uint16_t, 3>{0x11 * 257, 0x22 * 257, 0x33 * 257}));
  const Cloud ascii = readAll(
      dir.write("rgb.pcd", header("x y z rgb", "4 4 4 4", "F F F U", "1 1 1 1", 1, 1, "ascii") + "1 2 3 65280\n"));
  ASSERT_EQ(ascii.points.size(), 1u);
  EXPECT_EQ(ascii.points[0].rgb, (std::array<std::uint16_t, 3>{0, 65535, 0}));
}

TEST(PcdReader, IntensityIsRoundedAndClampedAsIs) {
  test::TempDirectory dir;
  const Cloud floats =
      readAll(dir.write("f.pcd", header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", 6, 1, "ascii") +
                                     "0 0 0 -3\n0 0 0 0.4\n0 0 0 0.6\n0 0 0 1000.5\n0 0 0 70000\n"
                                     "0 0 0 NaN\n"));
  std::vector<std::uint16_t> got;
  for (const auto& point : floats.points) got.push_back(point.intensity);
  EXPECT_EQ(got, (std::vector<std::uint16_t>{0, 0, 1, 1001, 65535, 0}));
  std::string records;
  for (const std::int32_t v : {-5, 200, 70000}) {
    for (const float c : {1.0f, 2.0f, 3.0f}) put(records, c);
    put(records, v);
  }
  const Cloud ints =
      readAll(dir.write("i.pcd", header("x y z intensity", "4 4 4 4", "F F F I", "1 1 1 1", 3, 1, "binary") + records));
  ASSERT_EQ(ints.points.size(), 3u);
  EXPECT_EQ(ints.points[0].intensity, 0);
  EXPECT_EQ(ints.points[1].intensity, 200);
  EXPECT_EQ(ints.points[2].intensity, 65535);
}

TEST(PcdReader, NormalsNeedAllThreeFields) {
  test::TempDirectory dir;
  const Cloud full = readAll(dir.write(
      "n.pcd", header("x y z normal_x normal_y normal_z", "4 4 4 8 8 8", "F F F F F F", "1 1 1 1 1 1", 1, 1, "ascii") +
                   "1 2 3 0.5 -0.5 0.25\n"));
  ASSERT_EQ(full.normals.size(), 1u);
  EXPECT_EQ(full.normals[0], (std::array<float, 3>{0.5f, -0.5f, 0.25f}));
  const Cloud partial = readAll(
      dir.write("p.pcd", header("x y z normal_x", "4 4 4 4", "F F F F", "1 1 1 1", 1, 1, "ascii") + "1 2 3 1\n"));
  EXPECT_FALSE(partial.info.attributes.normals);
  EXPECT_TRUE(partial.normals.empty());
  EXPECT_EQ(partial.info.ignored_fields, std::vector<std::string>{"normal_x (F4)"});
}

TEST(PcdReader, DoubleCoordinatesKeepUtmExactly) {
  const std::array<double, 3> utm = {512345.678901, 5403210.987654, 245.001};
  std::string records;
  for (const double v : utm) put(records, v);
  test::TempDirectory dir;
  const Cloud binary =
      readAll(dir.write("d.pcd", header("x y z", "8 8 8", "F F F", "1 1 1", 1, 1, "binary") + records));
  const Cloud ascii = readAll(dir.write(
      "a.pcd", header("x y z", "8 8 8", "F F F", "1 1 1", 1, 1, "ascii") + "512345.678901 5403210.987654 245.001\n"));
  for (const Cloud* cloud : {&binary, &ascii}) {
    ASSERT_EQ(cloud->points.size(), 1u);
    EXPECT_EQ(cloud->points[0].x, utm[0]);
    EXPECT_EQ(cloud->points[0].y, utm[1]);
    EXPECT_EQ(cloud->points[0].z, utm[2]);
  }
}

TEST(PcdReader, IntegerCoordinateTypes) {
  std::string records;
  put(records, std::int8_t{-7});
  put(records, std::uint16_t{65000});
  put(records, std::int64_t{-123456789012});
  test::TempDirectory dir;
  const Cloud cloud = readAll(dir.write("i.pcd", header("x y z", "1 2 8", "I U I", "1 1 1", 1, 1, "binary") + records));
  ASSERT_EQ(cloud.points.size(), 1u);
  EXPECT_EQ(cloud.points[0].x, -7.0);
  EXPECT_EQ(cloud.points[0].y, 65000.0);
  EXPECT_EQ(cloud.points[0].z, -123456789012.0);
}

TEST(PcdReader, OrganizedCloudCountsNanPixels) {
  // 4 x 3 pixels, '.' invalid (NaN):   # . # #
  //                                    . . # #
  //                                    # # # .
  const std::string mask =
      "#.##"
      "..##"
      "###.";
  std::string records;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const float v = mask[i] == '#' ? static_cast<float>(i) : std::nanf("");
    for (int k = 0; k < 3; ++k) put(records, v);
  }
  test::TempDirectory dir;
  const std::string binary = dir.write("b.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 4, 3, "binary") + records);
  const std::string compressed =
      dir.write("c.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 4, 3, "binary_compressed") +
                             compressedData(records, {4, 4, 4}) + std::string(300, '\0'));  // PCL's zero padding
  for (const std::string& path : {binary, compressed}) {
    const Cloud cloud = readAll(path);
    EXPECT_EQ(cloud.info.declared_points, 12u);
    EXPECT_EQ(cloud.counts.delivered, 8u);
    EXPECT_EQ(cloud.counts.non_finite, 4u);
    ASSERT_EQ(cloud.points.size(), 8u);
    EXPECT_EQ(cloud.points[1].x, 2.0);
  }
}

TEST(PcdReader, DeliversBoundedBatchesInOrder) {
  // 1000 points; points 100..299 are NaN, so a batch fills from beyond them.
  std::string records;
  std::string ascii = header("x y z", "4 4 4", "F F F", "1 1 1", 1000, 1, "ascii");
  for (int i = 0; i < 1000; ++i) {
    const float v = i >= 100 && i < 300 ? std::nanf("") : static_cast<float>(i);
    for (int k = 0; k < 3; ++k) put(records, v);
    ascii += text(v) + " " + text(v) + " " + text(v) + "\n";
  }
  test::TempDirectory dir;
  const std::string head = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1000\nPOINTS 1000\nDATA ";
  for (const std::string& path :
       {dir.write("a.pcd", ascii), dir.write("b.pcd", head + "binary\n" + records),
        dir.write("c.pcd", head + "binary_compressed\n" + compressedData(records, {4, 4, 4}))}) {
    const Cloud cloud = readAll(path, 64);
    ASSERT_EQ(cloud.points.size(), 800u);
    EXPECT_EQ(cloud.counts.non_finite, 200u);
    EXPECT_EQ(cloud.batch_sizes.size(), 13u);  // 12 full batches of 64, then 32
    for (std::size_t b = 0; b + 1 < cloud.batch_sizes.size(); ++b) EXPECT_EQ(cloud.batch_sizes[b], 64u);
    EXPECT_EQ(cloud.batch_sizes.back(), 32u);
    EXPECT_EQ(cloud.points[99].x, 99.0);
    EXPECT_EQ(cloud.points[100].x, 300.0);
    EXPECT_EQ(cloud.points.back().x, 999.0);
  }
}

TEST(PcdReader, HeaderVariants) {
  test::TempDirectory dir;
  const std::string body =
      "FIELDS x y z\n# a comment\n\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nPOINTS 2\nDATA ascii\n"
      "1 2 3\n\n4 5 6\n\n";
  EXPECT_EQ(readAll(dir.write("v7.pcd", "VERSION .7\n" + body)).info.format, "PCD 0.7 ascii");
  EXPECT_EQ(readAll(dir.write("v6.pcd", "VERSION 0.6\n" + body)).info.format, "PCD 0.6 ascii");
  const Cloud bare = readAll(dir.write("none.pcd", body));
  EXPECT_EQ(bare.info.format, "PCD ascii");
  EXPECT_EQ(bare.points.size(), 2u);
  EXPECT_EQ(bare.points[1].z, 6.0);
  EXPECT_EQ(openPointCloud(dir.write("v7.pcd", "VERSION .7\n" + body))->info().format, "PCD 0.7 ascii");
}

// --- errors ------------------------------------------------------------------------------------

// Opens and reads `content` to the end; the error it throws must name the file and contain `parts`.
void expectError(const std::string& content, const std::vector<std::string>& parts) {
  test::TempDirectory dir;
  const std::string path = dir.write("bad.pcd", content);
  try {
    readAll(path);
    ADD_FAILURE() << "expected an error containing '" << parts.front() << "'";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

const std::string kXyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

TEST(PcdReaderErrors, HeaderLines) {
  expectError("FIELDS x y z\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n", {"line 5", "no SIZE line"});
  expectError(kXyz + "WIDTH abc\nPOINTS 1\nDATA ascii\n", {"line 5", "expected 'WIDTH <count>'"});
  expectError(kXyz + "WIDTH 1\nWIDTH 1\n", {"line 6", "a second WIDTH"});
  expectError(kXyz + "WIDTH 1\nVIEWPOINT 0 0 0\n", {"line 6", "VIEWPOINT"});
  expectError("hello world\n", {"line 1", "unknown header line 'hello world'"});
  expectError(kXyz + "WIDTH 1\nPOINTS 1\n", {"truncated header"});
  expectError("VERSION 0.9\n" + kXyz + "WIDTH 1\nPOINTS 1\nDATA ascii\n", {"line 1", "unsupported PCD VERSION"});
}

TEST(PcdReaderErrors, FieldLists) {
  expectError("FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n",
              {"line 2", "SIZE has 2 values but FIELDS names 3"});
  expectError("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1 1\nWIDTH 1\nPOINTS 1\nDATA ascii\n",
              {"line 4", "COUNT has 4 values"});
  expectError("FIELDS x y z\nSIZE 4 4 4\nTYPE F F X\nWIDTH 1\nPOINTS 1\nDATA ascii\n", {"line 3", "unknown TYPE 'X'"});
  expectError("FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n",
              {"line 2", "invalid SIZE '2' for field z of TYPE F"});
  expectError("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\nWIDTH 1\nPOINTS 1\nDATA ascii\n",
              {"line 4", "invalid COUNT '0'"});
  expectError("FIELDS x y intensity\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n", {"lack x, y or z"});
  expectError("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 2 1\nWIDTH 1\nPOINTS 1\nDATA ascii\n", {"COUNT 2"});
}

TEST(PcdReaderErrors, CountsAndDataKind) {
  expectError(kXyz + "WIDTH 4\nHEIGHT 3\nPOINTS 11\nDATA ascii\n",
              {"line 7", "POINTS 11 disagrees with WIDTH 4 x HEIGHT 3"});
  expectError(kXyz + "WIDTH 1\nPOINTS 1\nDATA binary_lzma\n", {"line 7", "unknown DATA kind 'binary_lzma'"});
}

TEST(PcdReaderErrors, BinarySizeIsCheckedAtOpen) {
  const std::string head = kXyz + "WIDTH 3\nPOINTS 3\nDATA binary\n";
  const std::string at = "at byte " + std::to_string(head.size());
  expectError(head + std::string(35, '\0'), {at, "truncated", "enough for 2 points"});
  expectError(head + std::string(37, '\0'), {"at byte " + std::to_string(head.size() + 36), "1 bytes of surplus"});
}

TEST(PcdReaderErrors, AsciiLines) {
  const std::string head = kXyz + "WIDTH 2\nPOINTS 2\nDATA ascii\n";
  expectError(head + "1 2 3\n1 2\n", {"line 9", "2 values where the header declares 3"});
  expectError(head + "1 2 3\n1 2 abc\n", {"line 9", "'abc' is not a number (field z, point 2)"});
  expectError(head + "1 2 3\n4 5 6\n\n7 8 9\n", {"line 11", "surplus data after the 2 declared points"});
  expectError(head + "1 2 3\n", {"truncated", "ends after 1"});
}

TEST(PcdReaderErrors, CompressedBlocks) {
  const std::string head = kXyz + "WIDTH 1\nPOINTS 1\nDATA binary_compressed\n";
  const auto block = [](std::uint32_t compressed, std::uint32_t uncompressed, const std::string& data) {
    std::string out;
    put(out, compressed);
    put(out, uncompressed);
    return out + data;
  };
  const std::string literal12 = std::string(1, '\x0b') + std::string(12, 'a');
  expectError(head + block(13, 13, literal12), {"holds 13 bytes uncompressed", "12 bytes"});
  expectError(head + block(14, 12, literal12), {"truncated", "14 bytes"});
  expectError(head + block(13, 12, literal12 + std::string(5, '\0') + "z"),
              {"at byte " + std::to_string(head.size() + 8 + 13 + 5), "surplus data after the compressed block"});
  expectError(head + block(3, 12,
                           std::string("\x00"
                                       "a"
                                       "\x3f",
                                       3)),
              {"corrupt LZF", "stopped after 1"});
  expectError(head + block(2, 12, std::string("\x20\x00", 2)), {"corrupt LZF"});
  expectError(head + "\x01\x00", {"truncated"});
  expectError(kXyz + "WIDTH 1000000000\nPOINTS 1000000000\nDATA binary_compressed\n" + block(1, 1, "a"), {"GiB"});
}

}  // namespace
}  // namespace plumb::io
