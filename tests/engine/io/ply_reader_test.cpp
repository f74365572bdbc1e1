#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "engine/core/error.h"
#include "engine/io/ply_writer.h"
#include "engine/io/point_reader.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

// Appends the bytes of `value`, big-endian when `big` is set.
template <typename T>
void put(std::string& out, T value, bool big = false) {
  auto bytes = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (big) std::reverse(bytes.begin(), bytes.end());
  out.append(bytes.data(), bytes.size());
}

std::vector<PointRecord> readAll(PointReader& reader, std::size_t batch_size = 1000) {
  std::vector<PointRecord> points;
  PointBatch batch;
  while (reader.read(batch, batch_size)) points.insert(points.end(), batch.points.begin(), batch.points.end());
  return points;
}

std::string errorOf(const std::string& path) {
  try {
    auto reader = openPly(path);
    readAll(*reader);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(PlyReader, BinaryLittleEndianWithColourIntensityAndIgnoredProperties) {
  test::TempDirectory dir;
  std::string file =
      "ply\nformat binary_little_endian 1.0\ncomment test\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nproperty float intensity\nproperty uchar label\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nend_header\n";
  for (int i = 0; i < 2; ++i) {
    put(file, 1.5f + static_cast<float>(i));
    put(file, -2.0f);
    put(file, 0.25f);
    put(file, 1000.4f * static_cast<float>(i + 1));
    put(file, std::uint8_t{7});
    put(file, std::uint8_t{255});
    put(file, std::uint8_t{0});
    put(file, std::uint8_t{static_cast<std::uint8_t>(100 + i)});
  }
  auto reader = openPly(dir.write("a.ply", file));
  EXPECT_EQ(reader->info().format, "PLY binary_little_endian");
  EXPECT_EQ(reader->info().declared_points, 2u);
  EXPECT_TRUE(reader->info().attributes.colour);
  EXPECT_TRUE(reader->info().attributes.intensity);
  EXPECT_FALSE(reader->info().attributes.normals);
  EXPECT_EQ(reader->info().ignored_fields, std::vector<std::string>{"label"});
  const auto points = readAll(*reader);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].x, 2.5);
  EXPECT_EQ(points[1].y, -2.0);
  EXPECT_EQ(points[1].z, 0.25);
  EXPECT_EQ(points[0].intensity, 1000);
  EXPECT_EQ(points[1].intensity, 2001);
  EXPECT_EQ(points[0].rgb, (std::array<std::uint16_t, 3>{65535, 0, 100 * 257}));
}

// The layouts most writers use (little-endian; x y z all double or all float; 8-bit colour;
// 16-bit intensity) are read without the general per-property decoding: the same records, the
// same skipped NaN, as the ascii file of the same values (which takes the general one).
TEST(PlyReader, TheCommonLayoutsReadAsTheGeneralDecodingDoes) {
  test::TempDirectory dir;
  constexpr int kPoints = 2500;
  const auto value = [](int i, int axis) {
    if (i == 1234 && axis == 1) return std::nan("");
    return (axis == 0 ? 512000.0 : 0.0) + 0.25 * i + 0.125 * axis;  // exact in a float and in ascii
  };
  const auto colour = [](int i, int c) { return static_cast<std::uint8_t>((i * 7 + c * 50) % 256); };
  const auto intensity = [](int i) { return static_cast<std::uint16_t>(i * 13 % 65536); };
  const std::string tail =
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar label\n"
      "property ushort intensity\nend_header\n";
  std::string doubles = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(kPoints) +
                        "\nproperty double x\nproperty double y\nproperty double z\n" + tail;
  std::string floats = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(kPoints) +
                       "\nproperty float x\nproperty float y\nproperty float z\n" + tail;
  std::string ascii = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(kPoints) +
                      "\nproperty double x\nproperty double y\nproperty double z\n" + tail;
  for (int i = 0; i < kPoints; ++i) {
    for (int a = 0; a < 3; ++a) {
      put(doubles, value(i, a));
      put(floats, static_cast<float>(value(i, a)));
      ascii += (std::isnan(value(i, a)) ? std::string("nan") : std::to_string(value(i, a))) + " ";
    }
    for (int c = 0; c < 3; ++c) {
      put(doubles, colour(i, c));
      put(floats, colour(i, c));
      ascii += std::to_string(colour(i, c)) + " ";
    }
    for (std::string* binary : {&doubles, &floats}) {
      put(*binary, std::uint8_t{9});
      put(*binary, intensity(i));
    }
    ascii += "9 " + std::to_string(intensity(i)) + "\n";
  }
  auto general = openPly(dir.write("ascii.ply", ascii));
  const auto expected = readAll(*general, 700);
  ASSERT_EQ(expected.size(), kPoints - 1u);
  EXPECT_EQ(general->counts().non_finite, 1u);
  for (const char* name : {"doubles.ply", "floats.ply"}) {
    auto reader = openPly(dir.write(name, name[0] == 'd' ? doubles : floats));
    const auto points = readAll(*reader, 700);
    ASSERT_EQ(points.size(), expected.size()) << name;
    EXPECT_EQ(reader->counts().non_finite, 1u) << name;
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_EQ(points[i].x, expected[i].x) << name << " " << i;
      EXPECT_EQ(points[i].y, expected[i].y) << name << " " << i;
      EXPECT_EQ(points[i].z, expected[i].z) << name << " " << i;
      EXPECT_EQ(points[i].rgb, expected[i].rgb) << name << " " << i;
      EXPECT_EQ(points[i].intensity, expected[i].intensity) << name << " " << i;
    }
  }
}

TEST(PlyReader, BigEndianDoublesInAnyPropertyOrderKeepUtmPrecision) {
  test::TempDirectory dir;
  std::string file =
      "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty ushort green\nproperty double z\n"
      "property ushort red\nproperty double x\nproperty ushort blue\nproperty double y\nend_header\n";
  put(file, std::uint16_t{2000}, true);
  put(file, 250.0005, true);
  put(file, std::uint16_t{1000}, true);
  put(file, 512000.0001, true);
  put(file, std::uint16_t{3000}, true);
  put(file, 5403000.0007, true);
  auto reader = openPly(dir.write("be.ply", file));
  const auto points = readAll(*reader);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].x, 512000.0001);
  EXPECT_EQ(points[0].y, 5403000.0007);
  EXPECT_EQ(points[0].z, 250.0005);
  EXPECT_EQ(points[0].rgb, (std::array<std::uint16_t, 3>{1000, 2000, 3000}));
}

TEST(PlyReader, AsciiWithNormalsSkipsOtherElementsAndCountsNaN) {
  test::TempDirectory dir;
  const std::string file =
      "ply\nformat ascii 1.0\nelement camera 1\nproperty list uchar float view\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "3 0.1 0.2 0.3\n"
      "1 2 3 0 0 1\n"
      "nan 2 3 0 0 1\n"
      "+4e0 5 -6 1 0 0\n"
      "3 0 1 2\n";
  auto reader = openPly(dir.write("a.ply", file));
  EXPECT_TRUE(reader->info().attributes.normals);
  PointBatch batch;
  ASSERT_TRUE(reader->read(batch, 10));
  ASSERT_EQ(batch.size(), 2u);
  ASSERT_EQ(batch.normals.size(), 2u);
  EXPECT_EQ(batch.points[1].x, 4.0);
  EXPECT_EQ(batch.points[1].z, -6.0);
  EXPECT_EQ(batch.normals[1], (std::array<float, 3>{1, 0, 0}));
  EXPECT_EQ(reader->counts().non_finite, 1u);
  EXPECT_EQ(reader->counts().delivered, 2u);
  EXPECT_FALSE(reader->read(batch, 10));
}

TEST(PlyReader, ReadsThePlyWriterOutputInBatches) {
  test::TempDirectory dir;
  const std::string path = dir.file("w.ply");
  {
    PlyWriter writer(
        path,
        {{"x", PlyType::kFloat64}, {"y", PlyType::kFloat64}, {"z", PlyType::kFloat64}, {"plane_id", PlyType::kUInt32}},
        {"round trip"});
    std::vector<std::byte> rows(writer.rowBytes() * 2500);
    std::byte* out = rows.data();
    for (int i = 0; i < 2500; ++i) {
      out = packLittleEndian(out, 512000.0 + i * 0.001);
      out = packLittleEndian(out, 5403000.0);
      out = packLittleEndian(out, static_cast<double>(i));
      out = packLittleEndian(out, static_cast<std::uint32_t>(i));
    }
    writer.writeRows(rows);
    writer.finish();
    writer.commit();
  }
  auto reader = openPly(path);
  PointBatch batch;
  std::size_t batches = 0, total = 0;
  double sum_z = 0.0;
  while (reader->read(batch, 1000)) {
    ++batches;
    total += batch.size();
    for (const auto& p : batch.points) sum_z += p.z;
  }
  EXPECT_EQ(batches, 3u);
  EXPECT_EQ(total, 2500u);
  EXPECT_EQ(sum_z, 2499.0 * 2500.0 / 2.0);
  EXPECT_EQ(reader->info().ignored_fields, std::vector<std::string>{"plane_id"});
}

TEST(PlyReader, MalformedFilesNameTheFileAndThePlace) {
  test::TempDirectory dir;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  std::string two_points = header;
  for (int i = 0; i < 6; ++i) put(two_points, 1.0f);
  std::string four_points = two_points;
  for (int i = 0; i < 6; ++i) put(four_points, 1.0f);

  struct Case {
    std::string name, content, expected;
  };
  const Case cases[] = {
      {"not.ply", "plx\nformat ascii 1.0\n", "must start with 'ply'"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "float128"},
      {"enc.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "binary_middle_endian"},
      {"novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n", "no 'vertex' element"},
      {"noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n", "lacks x, y or z"},
      {"truncated.ply", two_points, "truncated"},
      {"surplus.ply", four_points, "disagrees with the data"},
      {"ascii_short.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
       "1 2 3\n",
       "truncated"},
      {"ascii_values.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
       "1 2\n",
       "line 8"},
      {"ascii_word.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
       "1 two 3\n",
       "expected a number"},
      {"ascii_surplus.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
       "1 2 3\n4 5 6\n",
       "disagrees with the data"},
      {"empty.ply", "", "must start with 'ply'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write(c.name, c.content);
    const std::string message = errorOf(path);
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(path), std::string::npos) << c.name << ": " << message;
  }
  // The truncation is found at open time, right after the header.
  const std::string truncated = errorOf(dir.file("truncated.ply"));
  EXPECT_NE(truncated.find("at byte " + std::to_string(header.size())), std::string::npos) << truncated;
}

}  // namespace
}  // namespace plumb::io
