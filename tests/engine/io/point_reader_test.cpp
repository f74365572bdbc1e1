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

TEST(OpenPointCloud, RefusesLazAndUnknownFormatsClearly) {
  test::TempDirectory dir;
  const std::string laz = errorOf(dir.write("scan.laz", "LASF"));
  EXPECT_NE(laz.find("LAZ"), std::string::npos) << laz;
  EXPECT_NE(laz.find("scan.laz"), std::string::npos) << laz;
  const std::string unknown = errorOf(dir.write("model.e57", "ASTM-E57"));
  EXPECT_NE(unknown.find("unknown point-cloud format"), std::string::npos) << unknown;
  EXPECT_NE(errorOf(dir.file("absent.ply")).find("no such file"), std::string::npos);
}

}  // namespace
}  // namespace plumb::io
