// Tests of the E57 reader on the reference files in ../shared/data/formats/e57, written by
// libE57Format, the E57 reference implementation, cry-inc/e57 and PDAL's writers (the folder's
// README says where each comes from). No third-party decoder checked their points, so the tests
// check what must hold between files: the same bunny in six encodings decodes alike, two scans
// move by the poses added to their XML, a truncated or corrupt file stops with its offset.
// Each test skips when its file is absent.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/io/crc32c.h"
#include "engine/io/point_reader.h"
#include "tests/support/shared_data.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

struct Cloud {
  std::vector<PointRecord> points;
  std::vector<std::array<float, 3>> normals;
  CloudInfo info;
  ReadCounts counts;
};

Cloud readAll(const std::string& path) {
  auto reader = openPointCloud(path);
  Cloud cloud;
  PointBatch batch;
  while (reader->read(batch, 1000)) {
    cloud.points.insert(cloud.points.end(), batch.points.begin(), batch.points.end());
    cloud.normals.insert(cloud.normals.end(), batch.normals.begin(), batch.normals.end());
  }
  cloud.info = reader->info();
  cloud.counts = reader->counts();
  return cloud;
}

Eigen::Vector3d position(const PointRecord& p) {
  return {p.x, p.y, p.z};
}

// The message of the plumb::Error that reading `path` throws, or "" if it reads.
std::string errorReading(const std::string& path) {
  try {
    readAll(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// A copy of `source` in `dir` with the first `from` after the file header replaced by `to` (of
// the same length, so that no offset moves) in the pages' data, and every page's CRC-32C
// recomputed: a malformed file that passes the checksums, as no writer would make it.
std::string withEdit(const test::TempDirectory& dir, const std::string& source, const std::string& from,
                     const std::string& to) {
  EXPECT_EQ(from.size(), to.size());
  std::string file = readBytes(source);
  std::string logical;
  for (std::size_t page = 0; page < file.size(); page += 1024) logical += file.substr(page, 1020);
  const std::size_t at = logical.find(from, 48);
  EXPECT_NE(at, std::string::npos) << from << " not in " << source;
  if (at == std::string::npos) return source;
  logical.replace(at, from.size(), to);
  for (std::size_t page = 0; page * 1024 < file.size(); ++page) {
    file.replace(page * 1024, 1020, logical, page * 1020, 1020);
    const std::uint32_t crc = crc32c(std::as_bytes(std::span(file.data() + page * 1024, 1020)));
    for (int i = 0; i < 4; ++i)
      file[page * 1024 + 1020 + static_cast<std::size_t>(i)] = static_cast<char>(crc >> (24 - 8 * i));
  }
  const std::string path = dir.file(std::filesystem::path(source).stem().string() + "-edited.e57");
  writeBytes(path, file);
  return path;
}

TEST(E57Data, TheBunnyDecodesAlikeInEveryEncoding) {
  PLUMB_REQUIRE_FORMAT_FILE(reference_path, "e57/bunnyDouble.e57");
  const Cloud reference = readAll(reference_path);
  EXPECT_EQ(reference.info.declared_points, 30'571u);
  EXPECT_EQ(reference.counts.delivered + reference.counts.non_finite, 30'571u);
  ASSERT_GT(reference.points.size(), 30'000u);
  // A bunny about 0.15 m tall around the origin.
  Eigen::AlignedBox3d box;
  for (const PointRecord& p : reference.points) box.extend(position(p));
  EXPECT_GT(box.sizes().maxCoeff(), 0.1);
  EXPECT_LT(box.sizes().maxCoeff(), 0.3);
  // Single floats (a relative 6e-8 of coordinates under 0.2 m) and scaled integers of 19 to 32
  // bits with a step of 1 um (rounded by the writer: half a step).
  const std::vector<std::pair<std::string, double>> encodings{{"e57/bunnyFloat.e57", 2e-8},
                                                              {"e57/bunnyInt19.e57", 0.5e-6 + 1e-12},
                                                              {"e57/bunnyInt21.e57", 0.5e-6 + 1e-12},
                                                              {"e57/bunnyInt24.e57", 0.5e-6 + 1e-12},
                                                              {"e57/bunnyInt32.e57", 0.5e-6 + 1e-12}};
  for (const auto& [name, tolerance] : encodings) {
    PLUMB_REQUIRE_FORMAT_FILE(path, name);
    const Cloud cloud = readAll(path);
    ASSERT_EQ(cloud.points.size(), reference.points.size()) << name;
    EXPECT_EQ(cloud.counts.non_finite, reference.counts.non_finite) << name;
    double worst = 0.0;
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      worst = std::max(worst, (position(cloud.points[i]) - position(reference.points[i])).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(worst, tolerance) << name;
  }
}

TEST(E57Data, ScansMergeIntoOneCloudInTheWorldFrameByTheirPoses) {
  PLUMB_REQUIRE_FORMAT_FILE(plain_path, "e57/A_B.e57");
  PLUMB_REQUIRE_FORMAT_FILE(posed_path, "e57/A_B_with_poses.e57");
  const Cloud plain = readAll(plain_path);
  const Cloud posed = readAll(posed_path);
  EXPECT_EQ(posed.info.format, "E57 1.0, 2 scans");
  // 'B2 - Cloud' (2 points) moved by (-1, 2.5, 0); 'A4 - Cloud' (4 points) turned 90 degrees about
  // z and moved by (10, 20, 30).
  ASSERT_EQ(plain.points.size(), 6u);
  ASSERT_EQ(posed.points.size(), 6u);
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (std::size_t i = 0; i < 6; ++i) {
    const Eigen::Vector3d expected =
        i < 2 ? Eigen::Vector3d(position(plain.points[i]) + Eigen::Vector3d(-1.0, 2.5, 0.0))
              : Eigen::Vector3d(quarter * position(plain.points[i]) + Eigen::Vector3d(10, 20, 30));
    EXPECT_LT((position(posed.points[i]) - expected).norm(), 1e-9) << i;
    EXPECT_EQ(posed.points[i].rgb, plain.points[i].rgb) << i;
    // Each point keeps the index of its scan: the viewer colours by it.
    EXPECT_EQ(posed.points[i].scan, i < 2 ? 0 : 1) << i;
  }
  EXPECT_EQ(posed.info.scans, (std::vector<std::string>{"B2 - Cloud", "A4 - Cloud"}));
  EXPECT_TRUE(posed.info.attributes.colour);
}

TEST(E57Data, ColourAndIntensityAreNormalisedByTheirLimits) {
  PLUMB_REQUIRE_FORMAT_FILE(path, "e57/ColouredCubeFloat.e57");
  const Cloud cube = readAll(path);
  ASSERT_EQ(cube.points.size(), 7'680u);
  EXPECT_TRUE(cube.info.attributes.colour);
  EXPECT_FALSE(cube.info.attributes.intensity);
  // 8-bit colour (limits 0..255) on Plumb's 16-bit scale: multiples of 257, and both ends used.
  std::uint16_t lowest = 65535, highest = 0;
  for (const PointRecord& p : cube.points) {
    for (std::uint16_t c : p.rgb) {
      EXPECT_EQ(c % 257, 0) << c;
      lowest = std::min(lowest, c);
      highest = std::max(highest, c);
    }
  }
  EXPECT_EQ(lowest, 0);
  EXPECT_EQ(highest, 65535);
  PLUMB_REQUIRE_FORMAT_FILE(double_path, "e57/ColouredCubeDouble.e57");
  const Cloud twin = readAll(double_path);
  ASSERT_EQ(twin.points.size(), cube.points.size());
  for (std::size_t i = 0; i < cube.points.size(); ++i) {
    EXPECT_EQ(twin.points[i].rgb, cube.points[i].rgb);
    EXPECT_LT((position(twin.points[i]) - position(cube.points[i])).norm(), 1e-5);
  }
}

TEST(E57Data, IntensityOfAnyEncodingIsNormalisedByItsLimits) {
  // libE57Format's files: intensities -66 and 66 as an Integer with limits -66..66, and -66.6 and
  // 66.6 as a ScaledInteger (step 0.1) with limits -66.6..66.6: both ends of Plumb's scale.
  for (const char* name : {"e57/integer_intensity.e57", "e57/scaled_integer_intensity.e57"}) {
    PLUMB_REQUIRE_FORMAT_FILE(path, name);
    const Cloud cloud = readAll(path);
    EXPECT_TRUE(cloud.info.attributes.intensity) << name;
    ASSERT_EQ(cloud.points.size(), 2u) << name;
    EXPECT_EQ(cloud.points[0].intensity, 0) << name;
    EXPECT_EQ(cloud.points[1].intensity, 65535) << name;
  }
}

TEST(E57Data, SphericalCoordinatesBecomeCartesianAndInvalidPointsAreCounted) {
  // cry-inc's file: 360 records of range 1, every other one marked invalid (sphericalInvalidState).
  PLUMB_REQUIRE_FORMAT_FILE(path, "e57/tiny_spherical.e57");
  const Cloud cloud = readAll(path);
  EXPECT_EQ(cloud.info.declared_points, 360u);
  EXPECT_EQ(cloud.counts.delivered, 180u);
  EXPECT_EQ(cloud.counts.non_finite, 180u);
  ASSERT_EQ(cloud.points.size(), 180u);
  for (const PointRecord& p : cloud.points) EXPECT_NEAR(position(p).norm(), 1.0, 1e-6);
  // The first lies on the x axis (azimuth and elevation 0); the others sweep up and around.
  EXPECT_LT((position(cloud.points[0]) - Eigen::Vector3d::UnitX()).norm(), 1e-9);
  EXPECT_GT(cloud.points[45].z, 0.5);
}

TEST(E57Data, TheSurfaceNormalsExtensionIsRead) {
  PLUMB_REQUIRE_FORMAT_FILE(path, "e57/testWithNormals.e57");
  const Cloud cloud = readAll(path);
  EXPECT_TRUE(cloud.info.attributes.normals);
  ASSERT_EQ(cloud.points.size(), 2u);
  ASSERT_EQ(cloud.normals.size(), 2u);
  // pye57's file: two points (1, 0, 0) and (2, 0, 0) with nor:normalX/Y/Z near +z and +y.
  const Eigen::Vector3f up(cloud.normals[0][0], cloud.normals[0][1], cloud.normals[0][2]);
  const Eigen::Vector3f side(cloud.normals[1][0], cloud.normals[1][1], cloud.normals[1][2]);
  EXPECT_NEAR(up.norm(), 1.0f, 1e-3f);
  EXPECT_GT(up.z(), 0.999f);
  EXPECT_GT(side.y(), 0.999f);
}

TEST(E57Data, FilesWithoutPointsHaveNone) {
  for (const char* name : {"e57/empty.e57", "e57/empty_pc.e57", "e57/ZeroPoints.e57", "e57/ZeroPointsInvalid.e57",
                           "e57/PinholeImageWithDistortionParameters.e57"}) {
    PLUMB_REQUIRE_FORMAT_FILE(path, name);
    const Cloud cloud = readAll(path);
    EXPECT_TRUE(cloud.points.empty()) << name;
    EXPECT_EQ(cloud.info.declared_points, 0u) << name;
  }
  PLUMB_REQUIRE_FORMAT_FILE(images, "e57/PinholeImageWithDistortionParameters.e57");
  const Cloud cloud = readAll(images);
  ASSERT_FALSE(cloud.info.ignored_fields.empty());
  EXPECT_EQ(cloud.info.ignored_fields.back(), "images2D (3 images)");
}

TEST(E57Data, ACorruptFileStopsWithItsPageAndOffset) {
  PLUMB_REQUIRE_FORMAT_FILE(bad_crc, "e57/bad-crc.e57");
  EXPECT_NE(errorReading(bad_crc).find("at byte 0: page 0 fails its CRC-32C check"), std::string::npos)
      << errorReading(bad_crc);
  PLUMB_REQUIRE_FORMAT_FILE(corrupt, "e57/corrupt_crc.e57");
  EXPECT_NE(errorReading(corrupt).find("at byte 33792: page 33 fails its CRC-32C check"), std::string::npos)
      << errorReading(corrupt);
  PLUMB_REQUIRE_FORMAT_FILE(invalid_header, "e57/InvalidCVHeader.e57");
  EXPECT_NE(errorReading(invalid_header).find("section id 182"), std::string::npos) << errorReading(invalid_header);
}

TEST(E57Data, AMalformedFileStopsWithWhatIsWrongAndWhere) {
  test::TempDirectory dir;
  PLUMB_REQUIRE_FORMAT_FILE(bunny, "e57/bunnyInt19.e57");
  // A copy whose checksums still pass reads as the original: the edit helper itself is sound.
  EXPECT_EQ(readAll(withEdit(dir, bunny, "bunny", "bunny")).points.size(), readAll(bunny).points.size());
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> cases{
      {{"<cartesianY type=\"ScaledInteger\"", "<cartesianY type=\"ScaledIntegex\""},
       "XML section, /data3D/0/points/prototype/cartesianY: type 'ScaledIntegex', expected"},
      {{"minimum=\"-262144\"", "minimum=\"-26214x\""},
       "XML section, /data3D/0/points/prototype/cartesianX@minimum: '-26214x' is not a 64-bit integer"},
      {{"recordCount=\"30571\"", "recordCount=\"30579\""},
       "truncated: data3D[0] 'bunny' ends after 30571 of 30579 records"},
      {{"</prototype>", "</prototypx>"}, "XML section, byte "},
      {{"fileOffset=\"48\"", "fileOffset=\"40\""}, "compressed vector header: section id 0"}};
  for (const auto& [edit, message] : cases) {
    const std::string error = errorReading(withEdit(dir, bunny, edit.first, edit.second));
    EXPECT_NE(error.find(message), std::string::npos) << edit.second << ": " << error;
    EXPECT_NE(error.find("bunnyInt19-edited.e57"), std::string::npos) << "names the file: " << error;
  }
  // Cut after 100 pages: the header's length says so before anything is read.
  const std::string cut = dir.file("cut.e57");
  writeBytes(cut, readBytes(bunny).substr(0, 100 * 1024));
  EXPECT_NE(errorReading(cut).find("at byte 16: truncated: the header says 225280 bytes, the file has 102400"),
            std::string::npos)
      << errorReading(cut);
}

}  // namespace
}  // namespace plumb::io
