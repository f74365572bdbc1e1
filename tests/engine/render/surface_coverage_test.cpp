// Closed surfaces at every distance (issue 24, point 3): the renderer's pictures of the simulated
// office, the demo's own scan, against a reference that draws every point of the full-resolution
// cloud as a disc of its local spacing in the plane of its true surface
// (tests/support/surface_coverage.h). Inside any surface of the reference at most 1 % of the
// pixels may show background. Views: the demo's first view, walls from 0.6 m and 2 m, a floor at
// a grazing angle, the iso view of the whole building; each at the default point budget and at a
// tight one, where coarse nodes stand in for their children. Squares and single pixels are
// measured beside the surfels, for the comparison; the spill printed (pixels shown where the
// reference shows no surface within kMarginPx) counts gaps between the scanner's lines that the
// renderer closes and the reference does not; that edges stay sharp is held by
// PointRendererTest.CloseUpEdgesStaySharp, where the outline is known exactly.
//
// Release builds only (label accuracy): it simulates the 1 M-point office and measures every
// point's spacing, minutes under ASan.

#include "tests/support/surface_coverage.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/io/png_image.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "engine/render/overlay_scene.h"
#include "engine/render/point_renderer.h"
#include "engine/view/camera.h"
#include "engine/view/view_presets.h"
#include "reco/sim/simulation.h"
#include "tests/support/gpu_test.h"
#include "tests/support/shared_data.h"
#include "tests/support/simulated_truth.h"
#include "tests/support/temp_directory.h"

namespace plumb::render {
namespace {

// The demo's scan (ui/viewer/demo_scan.cpp): the office, 1 M points, 2 mm noise, seed 1, at
// survey coordinates.
const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);
constexpr int kWidth = 1280, kHeight = 720;
constexpr int kMarginPx = 3;                // pixels this far inside a reference surface count
constexpr std::uint64_t kMinPixels = 2000;  // a surface's share is judged from this many pixels
constexpr double kMaxBackground = 0.01;
const Rgba kMagenta{255, 0, 255, 255};                                // a background no point of the office has
constexpr const char* kShapeNames[] = {"point", "square", "surfel"};  // SplatShape's order

// From `from` to `to`, in the frame of a scene placed at `offset` (the office's by default).
view::Camera lookAt(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& offset = kOffset) {
  view::Camera camera;
  camera.position = offset + from;
  camera.target = offset + to;
  camera.viewport_width_px = kWidth;
  camera.viewport_height_px = kHeight;
  return camera;
}

struct NamedView {
  std::string name;
  view::Camera camera;
};

// A cloud as an octree, and the reference's view of it: every point with its surface, spacing
// and normal.
struct ReferenceScene {
  std::shared_ptr<const lod::Octree> octree;
  std::vector<test::LabelledPoint> points;
  std::vector<float> spacings;
  std::vector<Eigen::Vector3d> normals;
};

class SurfaceCoverageTest : public test::GpuTest {
 protected:
  static void SetUpTestSuite() {
    directory_ = std::make_unique<test::TempDirectory>("plumb_surface_coverage_test");
    reco::sim::SimulationRequest request;
    request.scene = "office";
    request.scanner.noise_m = 0.002;
    request.scanner.seed = 1;
    request.target_points = 1'000'000;
    request.offset = kOffset;
    request.points_path = directory_->file("office.ply");
    const reco::sim::SimulationReport report = reco::sim::simulate(request);

    lod::BuildOptions build;
    build.sources = lod::fileSources({request.points_path});
    build.output = directory_->file("office.plumb");
    lod::buildOctree(build);
    office_.octree = lod::Octree::open(build.output);

    // The simulator's labels: each point's true plane, whose normal is the point's.
    const std::vector<reco::PlaneRegression> planes = test::fitTruePlanes(
        request.points_path, report.planes, kOffset, [](const Eigen::Vector3d& p, std::uint32_t plane) {
          office_.points.push_back({p, plane});
        });
    for (const test::LabelledPoint& point : office_.points) {
      const reco::Plane fit = planes[point.surface].fit();
      office_.normals.push_back(fit.valid ? fit.normal : Eigen::Vector3d::UnitZ());
    }
    office_.spacings = test::localSpacings(office_.points, 0.1);
  }
  static void TearDownTestSuite() {
    office_ = {};
    room_.reset();
    directory_.reset();
  }

  // The coverage of the renderer's picture through `view` under `budget`, against `reference`
  // (of the scene through the view), printed; the picture kept for inspection with
  // PLUMB_TEST_IMAGES=DIR.
  test::SurfaceCoverage measure(const ReferenceScene& scene, const test::ReferenceImage& reference,
                                const NamedView& view, std::uint64_t budget, SplatShape shape) {
    lod::NodeCache nodes(scene.octree, std::uint64_t{512} << 20);
    PointRenderer renderer(*device_, *allocator_, nodes);
    RenderSettings settings;
    settings.background = kMagenta;
    settings.selection.point_budget = budget;
    settings.splat = shape;
    const FrameStats stats = renderer.renderComplete(view.camera, settings);
    const io::RgbaImage image = renderer.readColour();
    std::vector<bool> covered(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
    for (int row = 0; row < image.height; ++row) {
      for (int column = 0; column < image.width; ++column) {
        covered[static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) +
                static_cast<std::size_t>(column)] = image.pixel(column, row) != packRgba(kMagenta);
      }
    }

    std::vector<test::PixelClass> classes;
    const test::SurfaceCoverage coverage = test::measureCoverage(reference, covered, kMarginPx, kMinPixels, &classes);
    std::printf(
        "%-14s %-7s budget %9llu: %9llu points drawn, %8llu px inside %2llu surfaces, background %.2f %% "
        "(worst surface %u: %.2f %%), spill %.3f %%\n",
        view.name.c_str(), kShapeNames[static_cast<std::size_t>(shape)], static_cast<unsigned long long>(budget),
        static_cast<unsigned long long>(stats.points_drawn), static_cast<unsigned long long>(coverage.inside_pixels),
        static_cast<unsigned long long>(coverage.surfaces_measured), 100.0 * coverage.background,
        coverage.worst_surface, 100.0 * coverage.worst_background, 100.0 * coverage.spill);
    if (const char* directory = std::getenv("PLUMB_TEST_IMAGES")) {
      const std::string stem = std::string(directory) + "/coverage_" + view.name + "_" +
                               kShapeNames[static_cast<std::size_t>(shape)] + "_" + std::to_string(budget);
      io::writePng(image, stem + ".png");
      // The reference's surfaces in colours of their labels, and what the measure found: surface
      // shown (grey), holes (red), spill past the reference's outlines (blue).
      io::RgbaImage mask{reference.width, reference.height, std::vector<std::uint8_t>(4 * reference.surface.size())};
      io::RgbaImage found = mask;
      for (std::size_t i = 0; i < reference.surface.size(); ++i) {
        const std::uint32_t label = reference.surface[i];
        const std::uint32_t rgba = label == test::ReferenceImage::kBackground
                                       ? packRgba(kMagenta)
                                       : 0xFF000000u | ((label + 1) * 2654435761u & 0xFFFFFFu);
        constexpr std::array<std::uint32_t, 4> kClassColours{0xFF202020u, 0xFF808080u, 0xFF0000FFu, 0xFFFF8000u};
        const std::uint32_t class_rgba = kClassColours[static_cast<std::size_t>(classes[i])];
        for (std::size_t c = 0; c < 4; ++c) {
          mask.rgba[4 * i + c] = static_cast<std::uint8_t>(rgba >> (8 * c));
          found.rgba[4 * i + c] = static_cast<std::uint8_t>(class_rgba >> (8 * c));
        }
      }
      io::writePng(found, stem + "_found.png");
      io::writePng(mask, stem + "_reference.png");
    }
    return coverage;
  }

  // Surfels (the renderer's default) at both budgets, held to the targets; squares and single
  // pixels, printed for the comparison (docs/rendering.md).
  // max_background: the target, or a known shortfall that may not grow.
  void expectClosed(const NamedView& view, const ReferenceScene& scene = office_,
                    double max_background = kMaxBackground) {
    const test::ReferenceImage reference =
        test::renderReference(scene.points, scene.spacings, scene.normals, view.camera);
    for (const std::uint64_t budget : {std::uint64_t{2'000'000}, std::uint64_t{250'000}}) {
      const test::SurfaceCoverage coverage = measure(scene, reference, view, budget, SplatShape::kSurfel);
      EXPECT_GT(coverage.surfaces_measured, 0u) << view.name;
      EXPECT_LE(coverage.worst_background, max_background)
          << view.name << " at budget " << budget << ": surface " << coverage.worst_surface;
    }
    measure(scene, reference, view, 2'000'000, SplatShape::kSquare);
    measure(scene, reference, view, 2'000'000, SplatShape::kPoint);
  }

  // A real interior scan, PCL's room (112,586 points, 10 to 20 cm apart on its far wall, a
  // surfel's disc a hundred pixels and more across from 2 m). No truth: the reference takes each
  // point's normal from its 12 nearest, and the scan is one surface. Built on first use.
  static const ReferenceScene& realRoom(const std::string& path) {
    if (room_) return *room_;
    ReferenceScene& scene = room_.emplace();
    lod::BuildOptions build;
    build.sources = lod::fileSources({path});
    build.output = directory_->file("room.plumb");
    lod::buildOctree(build);
    scene.octree = lod::Octree::open(build.output);
    lod::NodeCache nodes(scene.octree, std::uint64_t{256} << 20);
    for (const lod::NodeInfo& info : scene.octree->nodes()) {
      const std::shared_ptr<const lod::NodePoints> points = nodes.get(info.key);
      for (std::size_t i = 0; i < points->size(); ++i) {
        const std::array<double, 3> p = points->position(i);
        scene.points.push_back({Eigen::Vector3d(p[0], p[1], p[2]), 0});
      }
    }
    scene.spacings = test::localSpacings(scene.points, 0.5);
    scene.normals = test::localNormals(scene.points, 0.5);
    return scene;
  }

  static inline std::unique_ptr<test::TempDirectory> directory_;
  static inline ReferenceScene office_;
  static inline std::optional<ReferenceScene> room_;
};

// The headless demo's first view: along the corridor, its near left wall a metre away.
TEST_F(SurfaceCoverageTest, TheDemosFirstViewIsClosed) {
  expectClosed({"demo_home", lookAt({0.8, 1.0, 1.6}, {6.0, 1.0, 1.2})});
}

TEST_F(SurfaceCoverageTest, AWallUpCloseIsClosed) {
  expectClosed({"wall_0.6m", lookAt({4.0, 0.6, 1.3}, {4.0, 0.0, 1.2})});
}

TEST_F(SurfaceCoverageTest, AnOfficeWallFromTwoMetresIsClosed) {
  expectClosed({"office_2m", lookAt({8.0, 5.0, 1.5}, {8.0, 7.0, 1.3})});
}

TEST_F(SurfaceCoverageTest, AFloorAtAGrazingAngleIsClosed) {
  expectClosed({"floor_grazing", lookAt({12.0, 1.0, 1.7}, {15.0, 1.0, 0.6})});
}

TEST_F(SurfaceCoverageTest, TheWholeBuildingIsClosed) {
  const lod::Box3 bounds = office_.octree->header().bounds;
  expectClosed({"iso", view::presetCamera(view::ViewPreset::kIso, Eigen::Vector3d(bounds.min.data()),
                                          Eigen::Vector3d(bounds.max.data()), kWidth, kHeight)});
}

// A view of the real room, whose coordinates are its own.
NamedView roomView(const std::string& name, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return {name, lookAt(from, to, Eigen::Vector3d::Zero())};
}

// Its far wall from 2 m (5.75 % background before discs of neighbourhoods that span no one plane
// were drawn at their full radius, and before the splat's wide pass: lavapipe had cut the
// biggest discs off part way) and from 4 m, and the room along its other axis.
TEST_F(SurfaceCoverageTest, ARealRoomScanFromTwoMetresIsClosed) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  expectClosed(roomView("room_2m", {6.1, 0.0, 0.2}, {8.1, 0.0, 0.0}), realRoom(path));
}

TEST_F(SurfaceCoverageTest, ARealRoomScanFromFourMetresIsClosed) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  expectClosed(roomView("room_4m", {4.1, 0.0, 0.2}, {8.1, 0.0, 0.0}), realRoom(path));
}

TEST_F(SurfaceCoverageTest, ARealRoomScanAlongItsOtherAxisIsClosed) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  expectClosed(roomView("room_y", {0.0, 0.0, 0.2}, {0.0, 4.0, 0.0}), realRoom(path));
}

// From 1 m a disc of the far wall is several hundred pixels across: 19 % showed background
// while lavapipe cut the widest discs off, then 2.09 % in crescents along the discs' rims while
// each node measured its discs among its own points and shrank them by the density its
// ancestors add, assumed even (now measured among the ancestors' points too).
TEST_F(SurfaceCoverageTest, ARealRoomScanFromOneMetreIsClosed) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  expectClosed(roomView("room_1m", {7.1, 0.0, 0.2}, {8.1, 0.0, 0.0}), realRoom(path));
}

}  // namespace
}  // namespace plumb::render
