#include "engine/io/point_reader.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

std::string errorOf(const std::string& path) {
  try {
    openPointCloud(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(OpenPointCloud, ChoosesTheReaderByContentThenExtension) {
  test::TempDirectory dir;
  // A PLY named .xyz is still a PLY.
  const auto ply = openPointCloud(dir.write("cloud.xyz",
                                            "ply\nformat ascii 1.0\nelement vertex 0\n"
                                            "property float x\nproperty float y\nproperty float z\n"
                                            "end_header\n"));
  EXPECT_EQ(ply->info().format, "PLY ascii");
  const auto xyz = openPointCloud(dir.write("points.TXT", "1 2 3\n"));
  EXPECT_EQ(xyz->info().format, "ASCII txt");
}

TEST(OpenPointCloud, RefusesTruncatedLazAndUnknownFormatsClearly) {
  test::TempDirectory dir;
  // LAZ goes to the LAS reader (content "LASF"), which names both in its header errors.
  const std::string laz = errorOf(dir.write("scan.laz", "LASF"));
  EXPECT_NE(laz.find("LAZ"), std::string::npos) << laz;
  EXPECT_NE(laz.find("scan.laz"), std::string::npos) << laz;
  EXPECT_NE(laz.find("truncated header"), std::string::npos) << laz;
  const std::string not_laz = errorOf(dir.write("other.laz", "ABCDEFGH"));
  EXPECT_NE(not_laz.find("not a LAS or LAZ file"), std::string::npos) << not_laz;
  // (An "ASTM-E57" file goes to the E57 reader now: an unknown format needs unknown content.)
  const std::string unknown = errorOf(dir.write("model.abc", "ABCDEFGH"));
  EXPECT_NE(unknown.find("unknown point-cloud format"), std::string::npos) << unknown;
  EXPECT_NE(errorOf(dir.file("absent.ply")).find("no such file"), std::string::npos);
}

}  // namespace
}  // namespace plumb::io
