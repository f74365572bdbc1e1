#include "engine/view/camera_json.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb::view {
namespace {

// The message of the error readCameraJson throws for `text`, or "" when it reads.
std::string errorFor(const test::TempDirectory& directory, const std::string& text) {
  const std::string path = directory.write("camera.json", text);
  try {
    readCameraJson(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

void expectError(const std::string& text, const std::vector<std::string>& parts) {
  test::TempDirectory directory;
  const std::string message = errorFor(directory, text);
  ASSERT_FALSE(message.empty()) << "no error for " << text;
  EXPECT_NE(message.find(directory.file("camera.json")), std::string::npos) << message;
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
}

// A valid file with `extra` fields appended (each starting with a comma).
std::string withFields(const std::string& extra) {
  return R"({"position": [1, 2, 3], "target": [1, 5, 3])" + extra + "}";
}

TEST(CameraJson, RoundTripsEveryFieldExactly) {
  test::TempDirectory directory;
  Camera camera;
  camera.position = {512003.123456789, 5403001.987654321, 251.000000001};
  camera.target = {512010.1, 5403007.3, 249.9};
  camera.up = {0.1, 0.2, 0.97};
  camera.projection = Projection::kOrthographic;
  camera.fov_deg = 47.123;
  camera.ortho_height_m = 12.5;
  camera.viewport_width_px = 1600;
  camera.viewport_height_px = 900;
  camera.near_m = 0.01;
  camera.far_m = 2500.0;
  const std::string path = directory.file("camera.json");
  writeCameraJson(camera, path);
  EXPECT_EQ(directory.entryCount(), 1u);  // no temporary left behind

  const Camera back = readCameraJson(path);
  EXPECT_EQ(back.position, camera.position);
  EXPECT_EQ(back.target, camera.target);
  EXPECT_EQ(back.up, camera.up);
  EXPECT_EQ(back.projection, camera.projection);
  EXPECT_EQ(back.fov_deg, camera.fov_deg);
  EXPECT_EQ(back.ortho_height_m, camera.ortho_height_m);
  EXPECT_EQ(back.viewport_width_px, camera.viewport_width_px);
  EXPECT_EQ(back.viewport_height_px, camera.viewport_height_px);
  EXPECT_EQ(back.near_m, camera.near_m);
  EXPECT_EQ(back.far_m, camera.far_m);

  const std::string text = test::readFile(path);
  EXPECT_NE(text.find(R"("format": "plumb-camera")"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("projection": "orthographic")"), std::string::npos) << text;
}

TEST(CameraJson, FillsDefaultsForOptionalFields) {
  test::TempDirectory directory;
  const Camera camera = readCameraJson(directory.write("camera.json", withFields("")));
  const Camera defaults;
  EXPECT_EQ(camera.position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(camera.target, Eigen::Vector3d(1, 5, 3));
  EXPECT_EQ(camera.up, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(camera.projection, Projection::kPerspective);
  EXPECT_EQ(camera.fov_deg, 60.0);
  EXPECT_EQ(camera.ortho_height_m, 10.0);
  EXPECT_EQ(camera.viewport_width_px, 1920);
  EXPECT_EQ(camera.viewport_height_px, 1080);
  EXPECT_EQ(camera.near_m, 0.05);
  EXPECT_EQ(camera.far_m, 10'000.0);
  EXPECT_EQ(camera.up, defaults.up);
  EXPECT_EQ(camera.fov_deg, defaults.fov_deg);
}

TEST(CameraJson, ReadsTheDocumentedExample) {
  test::TempDirectory directory;
  const Camera camera = readCameraJson(directory.write("camera.json", R"({
    "format": "plumb-camera", "version": 1, "projection": "perspective",
    "position": [512000.0, 5402996.0, 252.0], "target": [512000.0, 5403000.0, 251.5], "up": [0, 0, 1],
    "fov_deg": 60, "ortho_height_m": 10, "viewport": [1920, 1080], "near_m": 0.05, "far_m": 10000})"));
  EXPECT_EQ(camera.position, Eigen::Vector3d(512000.0, 5402996.0, 252.0));
  EXPECT_EQ(camera.fov_deg, 60.0);
}

TEST(CameraJson, MissingFileNamesIt) {
  test::TempDirectory directory;
  try {
    readCameraJson(directory.file("absent.json"));
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(directory.file("absent.json")), std::string::npos) << message;
    EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
    EXPECT_NE(message.find("No such file"), std::string::npos) << message;
  }
}

TEST(CameraJson, ADirectoryIsNotACameraFile) {
  test::TempDirectory directory;
  try {
    readCameraJson(directory.path().string());
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("is a directory"), std::string::npos) << error.what();
  }
}

TEST(CameraJson, ErrorsNameTheFieldOrTheByte) {
  // Not JSON: the byte offset from nlohmann.
  expectError(R"({"position": [1, 2, 3], "target": oops})", {"at byte 35", "not a JSON camera file"});
  expectError("", {"at byte", "not a JSON camera file"});
  expectError(R"({"position": [1, 2, 3)", {"at byte", "not a JSON camera file"});
  // Not an object, wrong format, versions.
  expectError("[1, 2, 3]", {"expected a JSON object", "array"});
  expectError(withFields(R"(, "format": "plumb-grow")"), {"field 'format'", "\"plumb-grow\"", "not a Plumb camera"});
  expectError(withFields(R"(, "format": 7)"), {"field 'format'"});
  expectError(withFields(R"(, "version": 2)"), {"field 'version'", "written by a newer Plumb", "update Plumb"});
  expectError(withFields(R"(, "version": 0)"), {"field 'version'", "positive whole number"});
  expectError(withFields(R"(, "version": "1")"), {"field 'version'", "positive whole number"});
  // Required fields.
  expectError(R"({"target": [1, 5, 3]})", {"field 'position'", "missing"});
  expectError(R"({"position": [1, 2, 3]})", {"field 'target'", "missing"});
  // Wrong types.
  expectError(R"({"position": [1, 2], "target": [1, 5, 3]})", {"field 'position'", "array of 3 numbers"});
  expectError(R"({"position": "here", "target": [1, 5, 3]})", {"field 'position'", "array of 3 numbers"});
  expectError(R"({"position": [1, 2, 3], "target": [1, "5", 3]})",
              {"field 'target[1]'", "expected a number", "string"});
  expectError(withFields(R"(, "fov_deg": "wide")"), {"field 'fov_deg'", "expected a number"});
  expectError(withFields(R"(, "projection": "fisheye")"),
              {"field 'projection'", "\"perspective\" or \"orthographic\""});
  expectError(withFields(R"(, "viewport": [1920])"), {"field 'viewport'", "[width, height]"});
  expectError(withFields(R"(, "viewport": [1920.5, 1080])"), {"field 'viewport[0]'", "whole number of pixels"});
  expectError(withFields(R"(, "viewport": [1920, 99999999999])"), {"field 'viewport[1]'", "out of range"});
  expectError(withFields(R"(, "fov": 60)"), {"field 'fov'", "unknown field"});
  // Non-finite numbers: JSON has no NaN literal and nlohmann rejects overflowing numbers.
  expectError(withFields(R"(, "near_m": NaN)"), {"at byte", "not a JSON camera file"});
  expectError(withFields(R"(, "far_m": 1e999)"), {"field 'far_m'", "not finite"});
  expectError(R"({"position": [1, 2, -1e400], "target": [1, 5, 3]})", {"field 'position'", "not finite"});
  // Geometry rules.
  expectError(R"({"position": [1, 2, 3], "target": [1, 2, 3]})", {"field 'target'", "from the position"});
  expectError(withFields(R"(, "up": [0, 1, 0])"), {"field 'up'", "parallel"});
  expectError(withFields(R"(, "up": [0, 0, 0])"), {"field 'up'", "zero vector"});
  expectError(withFields(R"(, "fov_deg": 180)"), {"field 'fov_deg'", "between 1e-6 degrees and 180"});
  expectError(withFields(R"(, "fov_deg": 0)"), {"field 'fov_deg'", "between 1e-6 degrees and 180"});
  expectError(withFields(R"(, "ortho_height_m": -1)"), {"field 'ortho_height_m'", "at least 1 micrometre"});
  // Found by the camera fuzz target: finite, positive, but 2 / height overflowed.
  expectError(withFields(R"(, "ortho_height_m": 1e-320)"), {"field 'ortho_height_m'", "at least 1 micrometre"});
  expectError(withFields(R"(, "viewport": [0, 1080])"), {"field 'viewport'", "positive"});
  expectError(withFields(R"(, "near_m": 0)"), {"field 'near_m'", "at least 1 micrometre"});
  expectError(withFields(R"(, "near_m": 5, "far_m": 1)"), {"field 'far_m'", "greater than near_m"});
}

TEST(CameraJson, RefusesToWriteAnInvalidCameraAndLeavesNoFile) {
  test::TempDirectory directory;
  Camera camera;
  camera.target = camera.position;
  EXPECT_THROW(writeCameraJson(camera, directory.file("camera.json")), Error);
  EXPECT_EQ(directory.entryCount(), 0u);
}

TEST(CameraJson, WriteFailureNamesThePath) {
  test::TempDirectory directory;
  const std::string path = directory.file("no/such/dir/camera.json");
  try {
    writeCameraJson(Camera{}, path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace plumb::view
