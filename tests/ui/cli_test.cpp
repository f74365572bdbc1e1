// The plumb executable as a user meets it: help, argument errors, exit codes, outputs.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "engine/io/png_image.h"
#include "tests/support/copc_mosaic.h"
#include "tests/support/shared_data.h"
#include "tests/support/simulated_truth.h"
#include "tests/support/temp_directory.h"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code;
  std::string out;
  std::string err;
};

class Cli : public ::testing::Test {
 protected:
  // Runs plumb with `arguments` (shell words), no standard input.
  Outcome plumb(const std::string& arguments) const {
    const fs::path out = directory_ / "stdout.txt", err = directory_ / "stderr.txt";
    const std::string command =
        std::string(PLUMB_BINARY) + " " + arguments + " </dev/null >" + out.string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    Outcome run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, plumb::test::readFile(out), plumb::test::readFile(err)};
    fs::remove(out);
    fs::remove(err);
    return run;
  }
  std::size_t entries() const { return temp_.entryCount(); }
  std::string path(const std::string& name) const { return (directory_ / name).string(); }

  plumb::test::TempDirectory temp_;
  fs::path directory_ = temp_.path();
};

TEST_F(Cli, HelpListsTheCommands) {
  const Outcome run = plumb("--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("simulate"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("plumb <command> --help"), std::string::npos) << run.out;
}

TEST_F(Cli, CommandHelpListsItsOptions) {
  const Outcome run = plumb("simulate --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* option : {"--scene", "--points", "--noise-mm", "--seed", "--offset", "--output", "--truth",
                             "--stations", "--rotate-deg", "--dropout", "--max-range"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
}

TEST_F(Cli, NoCommandIsAnErrorOnStderr) {
  const Outcome run = plumb("");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("subcommand"), std::string::npos) << run.err;
}

TEST_F(Cli, UnknownCommandIsAnError) {
  const Outcome run = plumb("teleport");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("teleport"), std::string::npos) << run.err;
}

TEST_F(Cli, BadArgumentsNameTheOption) {
  struct Case {
    std::string arguments, expected;
  };
  const std::string out = " -o " + path("x.ply");
  for (const Case& c :
       {Case{"simulate --points abc" + out, "--points"}, Case{"simulate --noise-mm nan" + out, "nan"},
        Case{"simulate --noise-mm -1" + out, "--noise-mm"},
        Case{"simulate --points 1000 --step-deg 0.1" + out, "--step-deg"},
        Case{"simulate --offset 1,2" + out, "--offset"}, Case{"simulate --offset 1,2,inf" + out, "--offset"},
        Case{"simulate --scene castle" + out, "castle"}, Case{"simulate --points 1000", "--output"},
        Case{"simulate --stations 7" + out, "7 were asked for"}}) {
    const Outcome run = plumb(c.arguments);
    EXPECT_NE(run.exit_code, 0) << c.arguments;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << c.arguments << "\n" << run.err;
    EXPECT_EQ(entries(), 0u) << c.arguments << " left output behind";
  }
}

TEST_F(Cli, SimulateWritesTheRequestedPointsAndTruth) {
  const Outcome run =
      plumb("simulate --scene room --noise-mm 2 --points 200000 --seed 1 --offset 512000,5403000,250 -o " +
            path("room.ply") + " --truth " + path("room.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("points per second"), std::string::npos) << run.out;

  const nlohmann::json truth = nlohmann::json::parse(plumb::test::readFile(path("room.json")));
  const auto written = truth["points"]["written"].get<double>();
  EXPECT_NEAR(written, 200'000.0, 2'000.0);
  const std::string ply = plumb::test::readFile(path("room.ply"));
  EXPECT_NE(ply.find("element vertex " + std::to_string(truth["points"]["written"].get<std::uint64_t>()) + "\n"),
            std::string::npos);
  EXPECT_EQ(truth["offset"][1].get<double>(), 5403000.0);
  EXPECT_EQ(entries(), 2u);
}

TEST_F(Cli, ImportMergesFilesAndInfoDescribesTheOctree) {
  ASSERT_EQ(plumb("simulate --points 50000 --offset 512000,5403000,250 -o " + path("room.ply")).exit_code, 0);
  std::ofstream(path("extra.xyz")) << "512001 5403001 251\n512002 5403002 251.5\nnan 1 2\n";
  const Outcome import = plumb("import " + path("room.ply") + " " + path("extra.xyz") + " -o " + path("site.plumb"));
  ASSERT_EQ(import.exit_code, 0) << import.err;
  EXPECT_NE(import.out.find("from 2 files"), std::string::npos) << import.out;
  EXPECT_NE(import.out.find("skipped  1 points without a valid position"), std::string::npos) << import.out;
  EXPECT_NE(import.out.find("ignored  " + path("room.ply") + ": plane_id"), std::string::npos) << import.out;

  const Outcome info = plumb("info --verify " + path("site.plumb"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("1 input points skipped"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("verified"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("spacing"), std::string::npos) << info.out;
  // Two files are two scans: each point keeps its own, and the renderer colours by it.
  EXPECT_NE(import.out.find("scans    2, each point keeps its scan"), std::string::npos) << import.out;
  EXPECT_NE(info.out.find(" intensity scan\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("scans     0  room.ply\n            1  extra.xyz\n"), std::string::npos) << info.out;
  const Outcome render =
      plumb("render " + path("site.plumb") + " --colour scan --view top --size 64x48 -o " + path("scans.png"));
  EXPECT_EQ(render.exit_code, 0) << render.err;
}

TEST_F(Cli, ImportOfABadFileNamesItAndLeavesNoOctree) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  std::ofstream(path("bad.ply")) << header << "short";
  const Outcome truncated = plumb("import " + path("bad.ply") + " -o " + path("site.plumb"));
  EXPECT_EQ(truncated.exit_code, 1);
  EXPECT_NE(truncated.err.find(path("bad.ply") + "' at byte " + std::to_string(header.size()) + ": truncated"),
            std::string::npos)
      << truncated.err;
  std::ofstream(path("scan.laz")) << "LASF";
  const Outcome laz = plumb("import " + path("scan.laz") + " -o " + path("site.plumb"));
  EXPECT_EQ(laz.exit_code, 1);
  EXPECT_NE(laz.err.find("LAZ"), std::string::npos) << laz.err;
  EXPECT_NE(plumb("import " + path("absent.ply") + " -o " + path("site.plumb")).exit_code, 0);
  EXPECT_EQ(entries(), 2u) << "only the two inputs";

  const Outcome info = plumb("info " + path("bad.ply"));
  EXPECT_EQ(info.exit_code, 1);
  EXPECT_NE(info.err.find("not a Plumb octree"), std::string::npos) << info.err;
}

TEST_F(Cli, AnInterruptedImportLeavesNothingBehind) {
  ASSERT_EQ(plumb("simulate --points 3000000 -o " + path("big.ply")).exit_code, 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::string input = path("big.ply"), output = path("site.plumb");
    ::execl(PLUMB_BINARY, PLUMB_BINARY, "import", input.c_str(), "-o", output.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Inside the build: once its output's temporary exists (not a guess at how long that takes).
  const auto building = [&] {
    for (const auto& entry : fs::directory_iterator(directory_)) {
      if (entry.path().filename().string().find("site.plumb.partial-") == 0) return true;
    }
    return false;
  };
  for (int waited_ms = 0; !building() && waited_ms < 120'000; waited_ms += 5) ::usleep(5'000);
  ::kill(child, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) GTEST_SKIP() << "the import finished before the interrupt";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
  EXPECT_EQ(entries(), 1u) << "only the input may remain: no octree, no temporary file";
}

// SIGKILL cannot be caught: the killed import's unfinished octree stays beside the output (its
// chunk files were unlinked when made), and the next import of the same file removes it and
// succeeds. Three kills at different moments of the build.
TEST_F(Cli, AKilledImportIsCleanedUpByTheNext) {
  ASSERT_EQ(plumb("simulate --points 3000000 -o " + path("big.ply")).exit_code, 0);
  const std::string input = path("big.ply"), output = path("site.plumb");
  int killed = 0;
  for (const int after_ms : {300, 800, 1500}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::execl(PLUMB_BINARY, PLUMB_BINARY, "import", input.c_str(), "-o", output.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    ::usleep(static_cast<useconds_t>(after_ms) * 1000);
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    if (WIFSIGNALED(status)) {
      ++killed;
      EXPECT_FALSE(fs::exists(output)) << "killed after " << after_ms << " ms: no octree may appear";
    }
    fs::remove(output);  // when the import finished before its kill
  }
  if (killed == 0) GTEST_SKIP() << "every import finished before its kill";
  const Outcome import = plumb("import " + input + " -o " + output);
  ASSERT_EQ(import.exit_code, 0) << import.err;
  EXPECT_EQ(plumb("info " + output + " --verify").exit_code, 0);
  EXPECT_EQ(entries(), 2u) << "the input and the octree: no temporary of the killed imports";
}

TEST_F(Cli, GrowFindsTheRoomCornerPlanesFromAPointFile) {
  ASSERT_EQ(plumb("simulate --points 300000 --noise-mm 2 --offset 512000,5403000,250 -o " + path("room.ply") +
                  " --truth " + path("room.json"))
                .exit_code,
            0);
  // Near the room's corner (7, 5, 2.5) and a little inside: the x+ wall, the y+ wall, the ceiling.
  // Clicked in a view from 3 m away along the room's diagonal (docs/camera-json.md).
  plumb::test::writeFile(path("camera.json"),
                         R"({"format": "plumb-camera", "version": 1, "position": [512005.1679, 5403003.1679, 250.6679],
                "target": [512006.9, 5403004.9, 252.4], "fov_deg": 60, "viewport": [1920, 1080]})");
  const Outcome grow = plumb("grow " + path("room.ply") + " --seed 512006.9,5403004.9,252.4 --camera " +
                             path("camera.json") + " --json " + path("grow.json") + " --gltf " + path("grow.glb"));
  ASSERT_EQ(grow.exit_code, 0) << grow.err;
  EXPECT_NE(grow.out.find("grew 3 segments"), std::string::npos) << grow.out;
  const nlohmann::json result = nlohmann::json::parse(plumb::test::readFile(path("grow.json")));
  EXPECT_EQ(result["format"], "plumb-grow");
  ASSERT_EQ(result["segments"].size(), 3u);
  for (const auto& segment : result["segments"]) {
    double largest = 0.0;
    for (const auto& c : segment["plane"]["normal"]) largest = std::max(largest, std::abs(c.get<double>()));
    EXPECT_GT(largest, 0.9999) << "room planes are axis-aligned";
    EXPECT_GT(segment["statistics"]["points"].get<double>(), 100.0);
    // The regression polygon: rings and a triangulation in world coordinates, and its area.
    EXPECT_GT(segment["statistics"]["area_m2"].get<double>(), 0.05);
    ASSERT_GE(segment["polygon"]["rings"].size(), 1u);
    EXPECT_GE(segment["polygon"]["rings"][0].size(), 3u);
    EXPECT_GE(segment["polygon"]["triangles"].size(), 1u);
  }
  // The view 3 m away gives the parameters --view-distance 3 gives.
  EXPECT_NEAR(result["parameters"]["seed_radius_m"].get<double>(), 0.616, 0.01);
  EXPECT_GE(result["timing"]["seeded_ms"].get<double>(), result["timing"]["first_progress_ms"].get<double>());
  EXPECT_GE(result["timing"]["converged_ms"].get<double>(), result["timing"]["seeded_ms"].get<double>());
  // The detail follows the data: the points lie about 2 cm apart on this room's walls, coarser
  // than the 3.2 mm pixel, so the click takes every point (docs/parameters.md).
  const double click_spacing = result["parameters"]["click_spacing_m"].get<double>();
  EXPECT_GT(click_spacing, 0.005);
  EXPECT_LT(click_spacing, 0.05);
  EXPECT_NEAR(result["parameters"]["pixel_m"].get<double>(), 0.0032, 0.0002);
  EXPECT_NE(grow.out.find(": every point"), std::string::npos) << grow.out;
  // The room corner where the three meet, within a few times the statistical limit of this scan
  // there: its three walls fitted on all their true points (tests/support/simulated_truth.h), whose
  // corner is expected about 0.01 mm off at 2 mm noise. The grow took every point near the click.
  ASSERT_EQ(result["corners"].size(), 1u);
  const auto& corner = result["corners"][0]["position"];
  const plumb::test::CornerLimit limit =
      plumb::test::SimulatedTruth(path("room.ply"), path("room.json")).cornerLimit({512007.0, 5403005.0, 252.5});
  const double error =
      (Eigen::Vector3d(corner[0].get<double>(), corner[1].get<double>(), corner[2].get<double>()) - limit.truth).norm();
  std::printf("corner %.4f mm from the truth; the limit's standard error %.4f mm (its fit %.4f mm off)\n", error * 1e3,
              limit.standard_error_m * 1e3, (limit.fitted - limit.truth).norm() * 1e3);
  EXPECT_LT(error, plumb::test::kEndToEndLimitFactor * limit.standard_error_m);
  EXPECT_EQ(result["edges"].size(), 3u);
  // The glTF binary: a GLB header ("glTF", version 2) and its declared length (tinygltf reads it
  // back in the glTF writer's own test).
  const std::string glb = plumb::test::readFile(path("grow.glb"));
  ASSERT_GE(glb.size(), 12u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(static_cast<unsigned char>(glb[4]), 2u);
  EXPECT_EQ(entries(), 5u) << "room.ply, room.json, camera.json, grow.json and grow.glb only";

  const Outcome behind =
      plumb("grow " + path("room.ply") + " --seed 512000.1,5403000.1,250.1 --camera " + path("camera.json"));
  EXPECT_EQ(behind.exit_code, 1);
  EXPECT_NE(behind.err.find("behind the camera"), std::string::npos) << behind.err;

  const Outcome bad = plumb("grow " + path("room.ply") + " --seed 1,2");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--seed takes 3 finite numbers"), std::string::npos) << bad.err;
}

TEST_F(Cli, OutputIntoAMissingFolderFailsCleanly) {
  const Outcome run = plumb("simulate --points 1000 -o " + path("nowhere/room.ply"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("nowhere/room.ply"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("plumb simulate: error:"), std::string::npos) << run.err;
  EXPECT_EQ(entries(), 0u);
}

// Off screen, no window system: the room from above at the size asked for, nothing else left.
TEST_F(Cli, RenderWritesTheViewAsAPng) {
  ASSERT_EQ(plumb("simulate --points 100000 --noise-mm 2 -o " + path("room.ply")).exit_code, 0);
  const Outcome run =
      plumb("render " + path("room.ply") + " --view top --size 320x200 --edl off -o " + path("top.png"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("wrote " + path("top.png")), std::string::npos) << run.out;
  const plumb::io::RgbaImage image = plumb::io::readPng(path("top.png"));
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 200);
  // The room's 7 x 5 m fill the 320 x 200 view, less the margin; the ceiling's scan lines cover
  // about half of its pixels (100,000 points are few).
  std::size_t lit = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) lit += image.pixel(x, y) != image.pixel(0, 0);
  }
  EXPECT_GT(lit, std::size_t{320 * 200 * 4 / 10});
  EXPECT_EQ(entries(), 2u) << "room.ply and top.png only: the temporary octree is gone";

  // A camera file gives the view and, without --size, the image size.
  plumb::test::writeFile(path("camera.json"),
                         R"({"format": "plumb-camera", "version": 1, "position": [3.5, 2.5, 1.5],
                "target": [7.0, 5.0, 1.0], "fov_deg": 70, "viewport": [200, 120]})");
  const Outcome inside =
      plumb("render " + path("room.ply") + " --camera " + path("camera.json") + " -o " + path("inside.png"));
  ASSERT_EQ(inside.exit_code, 0) << inside.err;
  const plumb::io::RgbaImage view = plumb::io::readPng(path("inside.png"));
  EXPECT_EQ(view.width, 200);
  EXPECT_EQ(view.height, 120);
}

// 1234567 as "1,234,567", as plumb prints counts.
std::string withCommas(std::uint64_t value) {
  const std::string digits = std::to_string(value);
  std::string text;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
    text += digits[i];
  }
  return text;
}

// The non-background pixels' box of an image: its width and height in pixels.
std::array<int, 2> litExtent(const plumb::io::RgbaImage& image) {
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.pixel(x, y) == image.pixel(0, 0)) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  return {x1 - x0 + 1, y1 - y0 + 1};
}

// Stray points do not shrink the picture: the standard views frame the cloud's bulk (the
// octree's framing box), so two returns 17 m above the 2.5 m room leave it as large as without
// them. A LAS input's header gives the bounds, which saves the import a pass.
TEST_F(Cli, StandardViewsFrameTheCloudWithoutItsStrayPoints) {
  ASSERT_EQ(plumb("simulate --points 100000 --noise-mm 2 --offset 512000,5403000,250 -o " + path("room.las")).exit_code,
            0);
  plumb::test::writeFile(path("strays.xyz"), "512003.5 5403002.5 269.5\n512003.6 5403002.5 269.6\n");
  const Outcome clean = plumb("import " + path("room.las") + " -o " + path("clean.plumb"));
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_NE(clean.out.find("bounds from the headers,"), std::string::npos) << clean.out;
  const Outcome strays = plumb("import " + path("room.las") + " " + path("strays.xyz") + " -o " + path("strays.plumb"));
  ASSERT_EQ(strays.exit_code, 0) << strays.err;
  EXPECT_NE(strays.out.find("(bounds 0."), std::string::npos) << "a text file states no bounds: " << strays.out;

  const Outcome info = plumb("info " + path("strays.plumb"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  // The bounds keep the strays; the framing box, printed after them, leaves them out.
  const std::size_t framing = info.out.find("  framing");
  ASSERT_NE(framing, std::string::npos) << info.out;
  EXPECT_NE(info.out.rfind(".. 269.600\n", framing), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find("269.6", framing), std::string::npos) << info.out;

  for (const std::string view : {"iso", "front", "side"}) {
    for (const std::string cloud : {"clean", "strays"}) {
      const Outcome run = plumb("render " + path(cloud + ".plumb") + " --view " + view +
                                " --size 320x200 --edl off -o " + path(cloud + "-" + view + ".png"));
      ASSERT_EQ(run.exit_code, 0) << run.err;
    }
    const std::array<int, 2> without = litExtent(plumb::io::readPng(path("clean-" + view + ".png")));
    const std::array<int, 2> with = litExtent(plumb::io::readPng(path("strays-" + view + ".png")));
    // Framed on the bounds, the room would be about a tenth as high (2.5 of 19.6 m).
    EXPECT_GT(without[1], 100) << view;
    EXPECT_NEAR(with[0], without[0], 0.05 * without[0]) << view;
    EXPECT_NEAR(with[1], without[1], 0.05 * without[1]) << view;
  }
}

// `plumb simulate -o X.plumb` builds the octree of the scan without a point file: the same cloud
// as the scan written to PLY and imported, and the truth beside it.
TEST_F(Cli, SimulateBuildsAnOctreeWithoutAPointFile) {
  const std::string scan = "simulate --points 150000 --seed 3 --offset 512000,5403000,250 ";
  const Outcome direct =
      plumb(scan + "-o " + path("room.plumb") + " --truth " + path("room.json") + " --memory-mb 128");
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  EXPECT_NE(direct.out.find("(octree"), std::string::npos) << direct.out;
  ASSERT_EQ(plumb(scan + "-o " + path("room.ply")).exit_code, 0);
  ASSERT_EQ(plumb("import " + path("room.ply") + " -o " + path("imported.plumb")).exit_code, 0);
  // An octree that cannot be written stops the command before it scans.
  const Outcome nowhere = plumb(scan + "-o " + path("missing/room.plumb"));
  EXPECT_NE(nowhere.exit_code, 0);
  EXPECT_NE(nowhere.err.find(path("missing/room.plumb")), std::string::npos) << nowhere.err;
  EXPECT_EQ(entries(), 4u) << "room.plumb, room.json, room.ply, imported.plumb: nothing else";

  const nlohmann::json truth = nlohmann::json::parse(plumb::test::readFile(path("room.json")));
  const Outcome built = plumb("info " + path("room.plumb"));
  const Outcome imported = plumb("info " + path("imported.plumb"));
  ASSERT_EQ(built.exit_code, 0) << built.err;
  const auto from = [](const std::string& text, const std::string& start, const std::string& end) {
    const std::size_t at = text.find(start);
    return at == std::string::npos ? std::string() : text.substr(at, text.find(end, at) - at);
  };
  const std::string points = from(built.out, "  points", "\n");
  EXPECT_EQ(points, "  points      " + withCommas(truth["points"]["written"].get<std::uint64_t>())) << built.out;
  EXPECT_EQ(from(built.out, "  bounds", "  cube"), from(imported.out, "  bounds", "  cube"));
  EXPECT_EQ(from(built.out, "  nodes", "\n"), from(imported.out, "  nodes", "\n"));
}

// A COPC file needs no import: info, grow and render open it in place, and leave no file behind.
TEST_F(Cli, CopcFilesOpenInPlace) {
  PLUMB_REQUIRE_FORMAT_FILE(copc, "copc/lone-star.copc.laz");
  const Outcome info = plumb("info --verify " + copc);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("format      COPC 1.0, LAZ 1.4 point format 6"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("points      518,862"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("verified"), std::string::npos) << info.out;

  const Outcome grow = plumb("grow " + copc + " --seed 515388.976,4918368.237,2325.016");
  ASSERT_EQ(grow.exit_code, 0) << grow.err;
  EXPECT_EQ(grow.out.find("imported"), std::string::npos) << grow.out;
  EXPECT_NE(grow.out.find("grew 1 segment"), std::string::npos) << grow.out;

  // A 2 x 2 mosaic has an empty root: the renderer draws the nodes below it.
  plumb::test::writeCopcMosaic(copc, 1, path("mosaic.copc.laz"));
  const Outcome render = plumb("render " + path("mosaic.copc.laz") +
                               " --view top --size 200x200 --colour elevation --edl off -o " + path("top.png"));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const plumb::io::RgbaImage image = plumb::io::readPng(path("top.png"));
  std::size_t lit = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) lit += image.pixel(x, y) != image.pixel(0, 0);
  }
  EXPECT_GT(lit, std::size_t{200 * 200 / 4}) << "the four copies cover about half of the view";
  EXPECT_EQ(entries(), 2u) << "the mosaic and top.png only";
}

TEST_F(Cli, RenderRejectsBadArgumentsAndWritesNothing) {
  ASSERT_EQ(plumb("simulate --points 20000 -o " + path("room.ply")).exit_code, 0);
  const Outcome size = plumb("render " + path("room.ply") + " --size 320by200 -o " + path("shot.png"));
  EXPECT_NE(size.exit_code, 0);
  EXPECT_NE(size.err.find("--size 320by200"), std::string::npos) << size.err;
  const Outcome view = plumb("render " + path("room.ply") + " --view aerial -o " + path("shot.png"));
  EXPECT_NE(view.exit_code, 0);
  EXPECT_NE(view.err.find("aerial"), std::string::npos) << view.err;
  const Outcome missing = plumb("render " + path("nothing.ply") + " -o " + path("shot.png"));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find(path("nothing.ply")), std::string::npos) << missing.err;
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"--slice 1,0", "--slice: the thickness must be above 0"},
           {"--slice 1", "--slice takes 2 finite numbers"},
           {"--clip-box 1,2,3,4,5,nan", "--clip-box takes 6 to 7 finite numbers"},
           {"--clip-box 1,2,3,4,5,-6", "--clip-box: each size must be above 0"},
           {"--clip-outside", "--clip-outside needs a --clip-box"},
           {"--clip-plane 0,0,1,0,0,0", "--clip-plane: the normal must not be 0"}}) {
    const Outcome clip = plumb("render " + path("room.ply") + " " + arguments + " -o " + path("shot.png"));
    EXPECT_NE(clip.exit_code, 0) << arguments;
    EXPECT_NE(clip.err.find(message), std::string::npos) << arguments << ": " << clip.err;
  }
  EXPECT_EQ(entries(), 1u) << "room.ply only";
}

// A grow keeps to the section: in the room's corner, with everything below 0.2 m sliced away,
// the floor does not grow, the two walls do.
TEST_F(Cli, GrowKeepsToTheSection) {
  ASSERT_EQ(plumb("simulate --points 300000 --noise-mm 2 -o " + path("room.ply")).exit_code, 0);
  auto grow = [&](const std::string& arguments) {
    const Outcome run = plumb("grow " + path("room.ply") + " --seed 0.3,0.3,0.3 --detail medium " + arguments +
                              " --json " + path("grow.json"));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(plumb::test::readFile(path("grow.json"))).at("segments");
  };
  auto levels = [](const nlohmann::json& segments) {
    int level = 0;
    for (const auto& segment : segments)
      level += std::abs(segment.at("plane").at("normal")[2].get<double>()) > 0.9 ? 1 : 0;
    return level;
  };
  const nlohmann::json whole = grow("");
  EXPECT_EQ(levels(whole), 1) << "the floor grows without a section";
  const nlohmann::json sliced = grow("--slice 0.2,3");
  EXPECT_EQ(levels(sliced), 0) << sliced.dump();
  EXPECT_EQ(sliced.size(), 2u) << "the two walls";
}

// A slice at window height seen from above is the room's plan: the walls' thin lines, no floor
// or ceiling; a clip box's outside leaves the room's shell without its middle.
TEST_F(Cli, RenderDrawsOnlyWhatTheClippingKeeps) {
  ASSERT_EQ(plumb("simulate --points 200000 --noise-mm 2 -o " + path("room.ply")).exit_code, 0);
  auto litFraction = [&](const std::string& arguments) {
    const Outcome run = plumb("render " + path("room.ply") + " --view top --size 320x200 --edl off " + arguments +
                              " -o " + path("shot.png"));
    EXPECT_EQ(run.exit_code, 0) << arguments << ": " << run.err;
    const plumb::io::RgbaImage image = plumb::io::readPng(path("shot.png"));
    std::size_t lit = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) lit += image.pixel(x, y) != image.pixel(0, 0);
    }
    return static_cast<double>(lit) / (image.width * image.height);
  };
  const double whole = litFraction("");
  const double plan = litFraction("--slice 1.15,0.1");
  // The simulated room is 7 x 5 m: its walls' lines at 1.2 m cover a few per cent of the view.
  EXPECT_GT(whole, 0.4);
  EXPECT_GT(plan, 0.005);
  EXPECT_LT(plan, 0.1);
  const double shell = litFraction("--clip-box 3.5,2.5,1.25,6.6,4.6,10 --clip-outside");
  EXPECT_GT(shell, plan);
  EXPECT_LT(shell, 0.3 * whole);
}

}  // namespace

namespace {

// plumb view where no display answers (no DISPLAY, no WAYLAND_DISPLAY): the headless demo.
TEST_F(Cli, ViewWithoutADisplayRunsTheHeadlessDemo) {
  const std::string environment =
      "env -u DISPLAY -u WAYLAND_DISPLAY XDG_CACHE_HOME=" + path("cache") + " PLUMB_GPU=cpu ";
  const std::string command = environment + PLUMB_BINARY + " view --headless-out " + path("demo.png") +
                              " </dev/null >" + path("out.txt") + " 2>" + path("err.txt");
  const int status = std::system(command.c_str());
  const std::string out = plumb::test::readFile(path("out.txt"));
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out << plumb::test::readFile(path("err.txt"));
  EXPECT_NE(out.find("no display here; running the headless demo instead"), std::string::npos) << out;
  EXPECT_NE(out.find("grew "), std::string::npos) << out;
  const plumb::io::RgbaImage image = plumb::io::readPng(path("demo.png"));
  EXPECT_EQ(image.width, 1280);
  EXPECT_EQ(image.height, 720);
  // The demo was made once into the cache: its octree and truth are there for the next run.
  std::size_t cached = 0;
  for (const auto& entry : fs::directory_iterator(path("cache") + "/plumb")) {
    cached += entry.path().extension() == ".plumb" || entry.path().extension() == ".json";
  }
  EXPECT_EQ(cached, 2u);

  // A script needs a window: said clearly, nothing else done.
  plumb::test::writeFile(path("session.json"), "[]");
  const std::string scripted = environment + PLUMB_BINARY + " view --script " + path("session.json") +
                               " </dev/null >/dev/null 2>" + path("err.txt");
  const int scripted_status = std::system(scripted.c_str());
  EXPECT_TRUE(WIFEXITED(scripted_status) && WEXITSTATUS(scripted_status) == 1);
  EXPECT_NE(plumb::test::readFile(path("err.txt")).find("--script needs a display"), std::string::npos);
}

}  // namespace
