#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/io/point_reader.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

struct Read {
  std::vector<PointRecord> points;
  std::vector<std::array<float, 3>> normals;
  std::unique_ptr<PointReader> reader;
};

Read readAll(const std::string& path, const ReaderOptions& options = {}) {
  Read result{{}, {}, openAscii(path, options)};
  PointBatch batch;
  while (result.reader->read(batch, 2)) {
    result.points.insert(result.points.end(), batch.points.begin(), batch.points.end());
    result.normals.insert(result.normals.end(), batch.normals.begin(), batch.normals.end());
  }
  return result;
}

std::string errorOf(const std::string& path, const ReaderOptions& options = {}) {
  try {
    readAll(path, options);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(AsciiReader, PlainXyzWithBlankLines) {
  test::TempDirectory dir;
  const auto read = readAll(dir.write("a.xyz", "1 2 3\n\n  4\t5 6  \r\n7 8 9"));
  ASSERT_EQ(read.points.size(), 3u);
  EXPECT_EQ(read.points[1].y, 5.0);
  EXPECT_EQ(read.points[2].z, 9.0);
  EXPECT_FALSE(read.reader->info().attributes.colour);
}

TEST(AsciiReader, PtsCountLineWithLeicaIntensityAndColour) {
  test::TempDirectory dir;
  const auto read = readAll(dir.write("scan.pts", "2\n1 2 3 -2048 255 0 10\n4 5 6 2047 1 2 3\n"));
  ASSERT_EQ(read.points.size(), 2u);
  EXPECT_EQ(read.reader->info().declared_points, 2u);
  EXPECT_TRUE(read.reader->info().attributes.intensity);
  EXPECT_TRUE(read.reader->info().attributes.colour);
  EXPECT_EQ(read.points[0].intensity, 0);
  EXPECT_EQ(read.points[1].intensity, 65520);
  EXPECT_EQ(read.points[0].rgb, (std::array<std::uint16_t, 3>{65535, 0, 10 * 257}));
}

TEST(AsciiReader, CsvHeaderNamesTheColumnsInAnyOrder) {
  test::TempDirectory dir;
  const auto read = readAll(dir.write("a.csv", "//Z,X,Y,Intensity,label\n3,1,2,500,9\n6, 4, 5, 600, 9\n"));
  ASSERT_EQ(read.points.size(), 2u);
  EXPECT_EQ(read.points[0].x, 1.0);
  EXPECT_EQ(read.points[0].z, 3.0);
  EXPECT_EQ(read.points[1].intensity, 600);
  EXPECT_EQ(read.reader->info().ignored_fields, std::vector<std::string>{"label"});
}

TEST(AsciiReader, ColumnsOptionOverridesDetection) {
  test::TempDirectory dir;
  ReaderOptions options;
  options.columns = "_,x,y,z,nx,ny,nz";
  const auto read = readAll(dir.write("a.txt", "99 1 2 3 0 0 1\n98 4 5 6 1 0 0\n"), options);
  ASSERT_EQ(read.points.size(), 2u);
  EXPECT_EQ(read.points[1].x, 4.0);
  ASSERT_EQ(read.normals.size(), 2u);
  EXPECT_EQ(read.normals[1], (std::array<float, 3>{1, 0, 0}));
}

TEST(AsciiReader, DetectsColumnsByCount) {
  test::TempDirectory dir;
  const auto seven = readAll(dir.write("seven.txt", "1 2 3 100 10 20 30\n"));
  EXPECT_EQ(seven.points[0].intensity, 100);
  EXPECT_EQ(seven.points[0].rgb[2], 30 * 257);
  const auto nine = readAll(dir.write("nine.txt", "1 2 3 10 20 30 0 1 0\n"));
  EXPECT_TRUE(nine.reader->info().attributes.normals);
  EXPECT_EQ(nine.normals[0], (std::array<float, 3>{0, 1, 0}));
}

TEST(AsciiReader, NonFinitePointsAreSkippedAndCounted) {
  test::TempDirectory dir;
  const auto read = readAll(dir.write("nan.xyz", "1 2 3\nnan 2 3\n1 -inf 3\n1 2 1e999\n4 5 6\n"));
  EXPECT_EQ(read.points.size(), 2u);
  EXPECT_EQ(read.reader->counts().non_finite, 3u);
}

TEST(AsciiReader, EmptyFileIsAnEmptyCloud) {
  test::TempDirectory dir;
  EXPECT_TRUE(readAll(dir.write("empty.xyz", "")).points.empty());
  EXPECT_TRUE(readAll(dir.write("blank.xyz", "\n \n")).points.empty());
}

TEST(AsciiReader, MalformedFilesNameTheLine) {
  test::TempDirectory dir;
  struct Case {
    std::string name, content, expected;
  };
  const Case cases[] = {
      {"ragged.xyz", "1 2 3\n4 5\n", "line 2: expected 3 values, found 2"},
      {"word.xyz", "1 2 3\n4 five 6\n", "line 2: 'five' in column 2 is not a number"},
      {"count.pts", "3\n1 2 3\n4 5 6\n", "declares 3 points but the file holds 2"},
      {"five.txt", "1 2 3 4 5\n", "5 columns: say what they are with --columns"},
      {"colour.txt", "1 2 3 10 300 20\n", "colour value '300' is outside 0..255"},
      {"header.csv", "a,b,c\n1,2,3\n", "lack x, y or z"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write(c.name, c.content);
    const std::string message = errorOf(path);
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(path), std::string::npos) << c.name << ": " << message;
  }
  ReaderOptions bad;
  bad.columns = "x,y,w";
  EXPECT_NE(errorOf(dir.write("opt.xyz", "1 2 3\n"), bad).find("unknown column 'w'"), std::string::npos);
}

}  // namespace
}  // namespace plumb::io
