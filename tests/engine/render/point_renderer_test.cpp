// The point renderer off screen on lavapipe (or the GPU PLUMB_GPU names) with validation on:
// renders of the wall scene (render_scene.h) checked pixel by pixel, eye-dome lighting on and
// off, picking against the scene's grid, the point budget, resizing, eviction and streaming.

#include "engine/render/point_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>

#include "engine/core/error.h"
#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_format.h"
#include "engine/render/palette.h"
#include "tests/engine/render/render_scene.h"
#include "tests/support/gpu_test.h"

namespace plumb::render {
namespace {

constexpr std::uint32_t kRed = 0xFF0000FF, kGreen = 0xFF00FF00, kBlue = 0xFFFF0000;  // RGBA, R lowest
constexpr int kWidth = 128, kHeight = 96;  // 3.1 cm pixels: every pixel of a wall holds points

std::array<int, 4> channels(std::uint32_t rgba) {
  return {int(rgba & 0xFF), int((rgba >> 8) & 0xFF), int((rgba >> 16) & 0xFF), int(rgba >> 24)};
}

// Colours match within `tolerance` per channel.
::testing::AssertionResult near(std::uint32_t actual, std::uint32_t expected, int tolerance = 1) {
  const auto a = channels(actual), e = channels(expected);
  for (std::size_t c = 0; c < 4; ++c) {
    if (std::abs(a[c] - e[c]) > tolerance) {
      return ::testing::AssertionFailure() << "RGBA " << a[0] << "," << a[1] << "," << a[2] << "," << a[3] << " is not "
                                           << e[0] << "," << e[1] << "," << e[2] << "," << e[3];
    }
  }
  return ::testing::AssertionSuccess();
}

// With PLUMB_TEST_IMAGES=DIR, the tests write their renders there to be looked at.
void keepForInspection(const io::RgbaImage& image, const std::string& name) {
  if (const char* directory = std::getenv("PLUMB_TEST_IMAGES"))
    io::writePng(image, std::string(directory) + "/" + name + ".png");
}

class PointRendererTest : public test::GpuTest {
 protected:
  static void SetUpTestSuite() {
    directory_ = std::make_unique<test::TempDirectory>("plumb_point_renderer_test");
    walls_ = lod::Octree::open(test::buildWallScene(*directory_));
    far_offset_ = {500'000.25, 5'000'000.5, 312.0};
    far_walls_ = lod::Octree::open(test::buildWallScene(*directory_, far_offset_, 4'000));
  }
  static void TearDownTestSuite() {
    walls_.reset();
    far_walls_.reset();
    directory_.reset();
  }

  static RenderSettings flat() {
    RenderSettings settings;
    settings.edl = false;
    return settings;
  }

  // The front view, in `colour` without eye-dome lighting, of a variant of the wall scene that
  // `source` makes; kept for inspection as `name`.
  io::RgbaImage renderVariant(lod::BuildSource source, ColourMode colour, const std::string& name) {
    const test::TempDirectory dir("plumb_" + name + "_test");
    lod::BuildOptions options;
    options.sources = {std::move(source)};
    options.output = dir.file(name + ".plumb");
    options.memory_mb = 64;
    lod::buildOctree(options);
    lod::NodeCache nodes(lod::Octree::open(options.output), 64 << 20);
    PointRenderer renderer(*device_, *allocator_, nodes);
    RenderSettings settings = flat();
    settings.colour = colour;
    renderer.renderComplete(test::wallSceneFront(kWidth, kHeight), settings);
    io::RgbaImage image = renderer.readColour();
    keepForInspection(image, name);
    return image;
  }

  // The walls through `camera` without eye-dome lighting, every node drawn; kept for inspection as `name`.
  io::RgbaImage renderFlat(const view::Camera& camera, const std::string& name) {
    lod::NodeCache nodes(walls_, 64 << 20);
    PointRenderer renderer(*device_, *allocator_, nodes);
    renderer.renderComplete(camera, flat());
    io::RgbaImage image = renderer.readColour();
    keepForInspection(image, name);
    return image;
  }

  static inline std::unique_ptr<test::TempDirectory> directory_;
  static inline std::shared_ptr<const lod::Octree> walls_, far_walls_;
  static inline test::SceneOffset far_offset_;
};

TEST_F(PointRendererTest, TheFrontViewShowsEachPlaneWhereItIs) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  renderer.renderComplete(camera, flat());
  const io::RgbaImage image = renderer.readColour();
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  const std::uint32_t background = 0xFF24201E;  // RenderSettings' default (30, 32, 36)
  struct Probe {
    double x, z;
    std::uint32_t colour;
  };
  const Probe probes[] = {
      {-2.0, 0.5, kRed},  {-2.5, 2.8, kRed},      {-0.5, 0.5, kRed},        {2.0, 0.5, kGreen},
      {2.5, 2.8, kGreen}, {0.5, 2.5, kGreen},     {-0.5, 1.5, kBlue},       {0.5, 1.2, kBlue},
      {0.0, 1.8, kBlue},  {0.0, 3.3, background}, {-2.0, -0.3, background},
  };
  for (const Probe& probe : probes) {
    const auto [column, row] = test::frontPixel(camera, probe.x, probe.z);
    EXPECT_TRUE(near(image.pixel(column, row), probe.colour)) << "at x " << probe.x << ", z " << probe.z;
  }
  // Every pixel of the walls is covered: the selection refines to 0.6 pixel spacing and the
  // resolve fills the one-pixel holes left.
  int empty = 0;
  for (int row = 0; row < kHeight; ++row) {
    for (int column = 0; column < kWidth; ++column) {
      const double z = 1.5 + (0.5 * kHeight - row - 0.5) * 4.0 / kHeight;
      if (z > 0.05 && z < 2.95 && image.pixel(column, row) == background) ++empty;
    }
  }
  EXPECT_EQ(empty, 0);
}

TEST_F(PointRendererTest, EyeDomeLightingOutlinesTheSquareAndLeavesFlatWallsAlone) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  renderer.renderComplete(camera, flat());
  const io::RgbaImage off = renderer.readColour();
  RenderSettings lit;
  lit.edl = true;
  renderer.renderComplete(camera, lit);
  const io::RgbaImage on = renderer.readColour();
  keepForInspection(off, "edl_off");
  keepForInspection(on, "edl_on");

  // Inside a wall every neighbour is as far as the pixel: no shading at all.
  for (const auto& [x, z] : {std::pair{-2.0, 0.5}, std::pair{2.0, 2.5}, std::pair{0.0, 1.5}}) {
    const auto [column, row] = test::frontPixel(camera, x, z);
    EXPECT_TRUE(near(on.pixel(column, row), off.pixel(column, row))) << "at x " << x << ", z " << z;
  }
  // Just outside the square, on the wall 2 m behind it, the square's pixels are nearer: dark.
  for (const auto& [x, z] : {std::pair{-1.02, 1.5}, std::pair{0.0, 2.02}, std::pair{1.02, 1.5}}) {
    const auto [column, row] = test::frontPixel(camera, x, z);
    const auto lit_channels = channels(on.pixel(column, row)), flat_channels = channels(off.pixel(column, row));
    const int brightest = std::max({flat_channels[0], flat_channels[1], flat_channels[2]});
    EXPECT_GT(brightest, 200) << "at x " << x << ", z " << z;
    EXPECT_LT(std::max({lit_channels[0], lit_channels[1], lit_channels[2]}), brightest / 2)
        << "at x " << x << ", z " << z;
  }
}

// Close up, the walls' 2 cm grid lies 1.8 pixels apart on screen (1.1 cm pixels): every pixel of
// the walls is covered.
TEST_F(PointRendererTest, CloseUpSurfacesStayClosed) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  constexpr int kCloseWidth = 480, kCloseHeight = 360;
  const view::Camera camera = test::wallSceneFront(kCloseWidth, kCloseHeight);
  const FrameStats stats = renderer.renderComplete(camera, flat());
  EXPECT_EQ(stats.points_drawn, test::wallScenePoints());
  const io::RgbaImage image = renderer.readColour();
  keepForInspection(image, "close_up");
  const std::uint32_t background = 0xFF24201E;
  int empty = 0;
  for (int row = 0; row < kCloseHeight; ++row) {
    for (int column = 0; column < kCloseWidth; ++column) {
      const double z = 1.5 + (0.5 * kCloseHeight - row - 0.5) * 4.0 / kCloseHeight;
      const double x = (column + 0.5 - 0.5 * kCloseWidth) * 4.0 / kCloseHeight;
      if (z > 0.05 && z < 2.93 && x > -3.9 && x < 3.9 && image.pixel(column, row) == background) ++empty;
    }
  }
  EXPECT_EQ(empty, 0);
  const auto [column, row] = test::frontPixel(camera, -0.3, 0.5);
  EXPECT_TRUE(near(image.pixel(column, row), kRed));
}

// A 400 x 300 orthographic close-up of the walls' front, `height_m` high, centred on (x, z).
view::Camera closeUpOfTheWalls(double height_m, double x, double z) {
  view::Camera camera = test::wallSceneFront(400, 300);
  camera.ortho_height_m = height_m;
  camera.position.x() = camera.target.x() = x;
  camera.position.z() = camera.target.z() = z;
  return camera;
}

// Surfels close a surface up to its outline and hardly past it: a close-up of the blue square's
// top right corner, 600 pixels to the metre. Its points lie on a 2 cm grid, the last ones at
// x = 0.98 and z = 1.98; each disc's radius is its 4th nearest neighbour's distance (2 cm inside,
// 2.8 cm along an edge, 4 cm at the corner and more where a node's border cuts the neighbours
// off), so the square shows up to x = 1 and z = 2 (where its grid's next row would be) and never
// a grid step beyond.
TEST_F(PointRendererTest, CloseUpEdgesStaySharp) {
  const view::Camera camera = closeUpOfTheWalls(0.5, 0.9, 1.9);
  const io::RgbaImage image = renderFlat(camera, "close_up_edge");
  const double metres_per_px = camera.ortho_height_m / camera.viewport_height_px;
  int holes = 0, spilled = 0, past_outline = 0;
  for (int row = 0; row < camera.viewport_height_px; ++row) {
    for (int column = 0; column < camera.viewport_width_px; ++column) {
      const double x = 0.9 + (column + 0.5 - 0.5 * camera.viewport_width_px) * metres_per_px;
      const double z = 1.9 - (row + 0.5 - 0.5 * camera.viewport_height_px) * metres_per_px;
      const bool blue = near(image.pixel(column, row), kBlue);
      if (x < 0.98 && z < 1.98 && !blue) ++holes;
      if (blue && (x > 1.0 || z > 2.0)) ++past_outline;
      if (blue && (x > 1.0 + test::kGridStep || z > 2.0 + test::kGridStep)) ++spilled;
    }
  }
  std::printf("%d holes, %d pixels past the outline, %d more than a grid step past it\n", holes, past_outline, spilled);
  EXPECT_EQ(holes, 0);
  EXPECT_EQ(spilled, 0);
  // Past the outline, the edges' discs: an edge point's reaches (sqrt(2) - 1) grid steps past it
  // (5 pixels), a corner's a step. On average less than 6.5 pixels along the 470 pixels of edge
  // in view (the top edge from column 0 to 260, the right one from row 90 down): 5.1 while each
  // node's discs were its own points' spacing shrunk by its ancestors' density assumed even, 6.0
  // since they are measured among its ancestors' points too (a sparse real scan seen from 1 m
  // closed: tests/engine/render/surface_coverage_test.cpp).
  EXPECT_LT(past_outline, 470 * 13 / 2) << past_outline << " pixels past the outline";
}

// A disc near the eye covers more pixels than lavapipe lets one invocation's loops run
// (65,535 iterations in all, silently): the splat hands such footprints to its wide pass, a row
// per invocation. Here every disc spans the whole 400 x 300 view (2 cm of wall, its grid step,
// are 300 pixels), and no pixel may show background.
TEST_F(PointRendererTest, DiscsWiderThanAnInvocationsLoopsAreCastWhole) {
  const view::Camera camera = closeUpOfTheWalls(0.02, 0.51, 1.01);
  const io::RgbaImage image = renderFlat(camera, "wide_discs");
  int holes = 0;
  for (int row = 0; row < camera.viewport_height_px; ++row) {
    for (int column = 0; column < camera.viewport_width_px; ++column)
      holes += near(image.pixel(column, row), kBlue) ? 0 : 1;
  }
  EXPECT_EQ(holes, 0);
}

// Intensity is grey by the points' intensity (30,000 of 65,535 here); elevation runs the ramp
// from the cloud's lowest point (z = 0, dark violet) to its highest (z = 3 m, yellow).
TEST_F(PointRendererTest, IntensityIsGreyAndElevationFollowsTheRamp) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  RenderSettings settings = flat();
  settings.colour = ColourMode::kIntensity;
  renderer.renderComplete(camera, settings);
  io::RgbaImage image = renderer.readColour();
  const auto low = test::frontPixel(camera, -2.0, 0.05), high = test::frontPixel(camera, 2.0, 2.95);
  EXPECT_TRUE(near(image.pixel(low[0], low[1]), 0xFF757575)) << "30000 / 65535 of 255 is 117";
  EXPECT_TRUE(near(image.pixel(high[0], high[1]), 0xFF757575));

  settings.colour = ColourMode::kElevation;
  renderer.renderComplete(camera, settings);
  image = renderer.readColour();
  const auto bottom = channels(image.pixel(low[0], low[1])), top = channels(image.pixel(high[0], high[1]));
  EXPECT_GT(bottom[2], bottom[1]) << "violet: more blue than green at the bottom";
  EXPECT_LT(bottom[0] + bottom[1] + bottom[2], 300);
  EXPECT_GT(top[0], 200) << "yellow at the top";
  EXPECT_GT(top[1], 180);
  EXPECT_LT(top[2], 120);
}

// A scanner's 8-bit intensities (0 to 255 across the walls, left to right), as many LAS files
// keep them: drawn over the sampled range (1st to 99th percentile), not over 0 to 65,535, which
// left such clouds nearly black.
TEST_F(PointRendererTest, IntensityIsSpreadOverTheCloudsOwnRange) {
  const io::RgbaImage image =
      renderVariant(test::generatedSource(test::wallScenePoints(),
                                          [](std::uint64_t i) {
                                            io::PointRecord point = test::wallScenePoint(i, {});
                                            point.intensity = static_cast<std::uint16_t>(
                                                std::lround(255.0 * std::clamp((point.x + 4.0) / 8.0, 0.0, 1.0)));
                                            return point;
                                          }),
                    ColourMode::kIntensity, "intensity_8_bit");
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  // The view spans x from -2.67 to 2.67 m: intensities 48 and 207 at x = -2.5 and 2.5 m, about 18 %
  // and 82 % of the range 3 to 252 (drawn over 0 to 65,535 both were black: 0.2 and 0.8 of 255).
  const auto left = test::frontPixel(camera, -2.5, 1.5), right = test::frontPixel(camera, 2.5, 1.5);
  const auto middle = test::frontPixel(camera, 0.05, 0.2);
  EXPECT_NEAR(channels(image.pixel(left[0], left[1]))[0], 46, 12);
  EXPECT_NEAR(channels(image.pixel(right[0], right[1]))[0], 209, 12);
  EXPECT_NEAR(channels(image.pixel(middle[0], middle[1]))[0], 129, 12);
}

// Segment colours: labels by the points' own colour (red wall 1, green wall 2, the square none)
// give each wall its own colour and leave the square grey; a new labelling replaces the old.
TEST_F(PointRendererTest, SegmentColoursFollowTheLabels) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  RenderSettings settings = flat();
  settings.colour = ColourMode::kSegment;
  auto labelling = [&](std::uint64_t version, std::uint32_t red_label) {
    auto labels = std::make_shared<SegmentLabels>();
    labels->version = version;
    for (const lod::NodeInfo& info : walls_->nodes()) {
      const auto points = nodes.get(info.key);
      std::vector<std::uint32_t>& node_labels = labels->nodes[info.key];
      for (const lod::PackedPoint& p : points->points)
        node_labels.push_back(p.rgb[0] > 0 ? red_label : p.rgb[1] > 0 ? 2 : 0);
    }
    return labels;
  };
  const auto red = test::frontPixel(camera, -2.0, 0.5), green = test::frontPixel(camera, 2.0, 0.5),
             square = test::frontPixel(camera, 0.0, 1.5);

  renderer.renderComplete(camera, settings);  // no labels yet: all grey
  io::RgbaImage image = renderer.readColour();
  EXPECT_TRUE(near(image.pixel(red[0], red[1]), 0xFF8C8C8C));
  EXPECT_TRUE(near(image.pixel(square[0], square[1]), 0xFF8C8C8C));

  renderer.setSegmentLabels(labelling(1, 1));
  renderer.renderComplete(camera, settings);
  image = renderer.readColour();
  const std::uint32_t first_red = image.pixel(red[0], red[1]);
  EXPECT_FALSE(near(first_red, image.pixel(green[0], green[1]), 20));
  EXPECT_FALSE(near(first_red, 0xFF8C8C8C, 20));
  EXPECT_TRUE(near(image.pixel(square[0], square[1]), 0xFF8C8C8C));

  renderer.setSegmentLabels(labelling(2, 7));  // the red wall becomes segment 7
  renderer.renderComplete(camera, settings);
  image = renderer.readColour();
  EXPECT_FALSE(near(image.pixel(red[0], red[1]), first_red, 20));
}

// Scan colours: the wall scene as three scans (the red wall, the green wall, the blue square),
// drawn in the palette's colours of scans 0, 1 and 2 (engine/render/palette.h), across nodes of
// several chunks; the one-scan scene is all in scan 0's colour.
TEST_F(PointRendererTest, ScanColoursTellTheScansApart) {
  const io::RgbaImage image =
      renderVariant(test::generatedSource(test::wallScenePoints(),
                                          [](std::uint64_t i) {
                                            io::PointRecord point = test::wallScenePoint(i, {});
                                            point.scan = point.rgb[0] > 0 ? 0 : point.rgb[1] > 0 ? 1 : 2;
                                            return point;
                                          },
                                          "walls.e57", {"red", "green", "blue"}),
                    ColourMode::kScan, "scan_colours");
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  auto rgba = [](std::uint32_t scan) {
    const std::array<float, 3> c = scanColour(scan);
    auto byte = [](float v) { return static_cast<std::uint32_t>(std::lround(v * 255.0f)); };
    return byte(c[0]) | byte(c[1]) << 8 | byte(c[2]) << 16 | 0xFF000000u;
  };
  const auto red = test::frontPixel(camera, -2.0, 0.5), green = test::frontPixel(camera, 2.0, 0.5),
             square = test::frontPixel(camera, 0.0, 1.5), high_green = test::frontPixel(camera, 2.5, 2.8);
  EXPECT_TRUE(near(image.pixel(red[0], red[1]), rgba(0), 2));
  EXPECT_TRUE(near(image.pixel(green[0], green[1]), rgba(1), 2));
  EXPECT_TRUE(near(image.pixel(high_green[0], high_green[1]), rgba(1), 2));
  EXPECT_TRUE(near(image.pixel(square[0], square[1]), rgba(2), 2));
  EXPECT_FALSE(near(rgba(0), rgba(1), 20));
  EXPECT_FALSE(near(rgba(1), rgba(2), 20));

  lod::NodeCache one_scan(walls_, 64 << 20);
  PointRenderer plain(*device_, *allocator_, one_scan);
  RenderSettings settings = flat();
  settings.colour = ColourMode::kScan;
  plain.renderComplete(camera, settings);
  const io::RgbaImage all_one = plain.readColour();
  EXPECT_TRUE(near(all_one.pixel(red[0], red[1]), rgba(0), 2));
  EXPECT_TRUE(near(all_one.pixel(square[0], square[1]), rgba(0), 2));
}

// Overlays over the wall scene: a translucent polygon on the red wall blends with it; one
// behind the wall and one behind the blue square are hidden; a line in front shows at its width;
// a marker behind the square shows only when drawn on top.
TEST_F(PointRendererTest, OverlaysBlendAndHideBehindTheCloud) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  auto rectangle = [](double x0, double x1, double y, double z0, double z1, Rgba colour) {
    OverlayScene::Polygon polygon;
    const Eigen::Vector3d a(x0, y, z0), b(x1, y, z0), c(x1, y, z1), d(x0, y, z1);
    polygon.triangles = {a, b, c, a, c, d};
    polygon.colour = colour;
    return polygon;
  };
  auto overlay = std::make_shared<OverlayScene>();
  overlay->polygons.push_back(rectangle(-3.0, -1.5, 5.0, 0.3, 0.9, {255, 255, 0, 128}));  // on the red wall
  overlay->polygons.push_back(rectangle(-3.0, -1.5, 6.0, 2.0, 2.6, {0, 255, 255, 255}));  // behind it
  overlay->polygons.push_back(rectangle(-0.5, 0.5, 5.0, 1.2, 1.8, {0, 255, 255, 255}));   // behind the square
  overlay->lines.push_back({{1.0, 4.0, 2.5}, {3.0, 4.0, 2.5}, {255, 255, 255, 255}, 3.0f, false});
  overlay->markers.push_back({{0.0, 5.0, 1.5}, {255, 0, 255, 255}, 9.0f, true});
  overlay->markers.push_back({{0.6, 5.0, 1.5}, {255, 0, 255, 255}, 9.0f, false});
  renderer.setOverlay(overlay);
  renderer.renderComplete(camera, flat());
  const io::RgbaImage image = renderer.readColour();
  keepForInspection(image, "overlays");
  auto at = [&](double x, double z) {
    const auto [column, row] = test::frontPixel(camera, x, z);
    return image.pixel(column, row);
  };
  EXPECT_TRUE(near(at(-2.2, 0.6), 0xFF0080FF, 2)) << "half yellow over red";
  EXPECT_TRUE(near(at(-2.2, 2.3), kRed)) << "the polygon behind the wall is hidden";
  EXPECT_TRUE(near(at(0.0, 1.3), kBlue)) << "the polygon behind the square is hidden";
  EXPECT_TRUE(near(at(2.0, 2.5), 0xFFFFFFFF)) << "the line";
  EXPECT_TRUE(near(at(2.0, 2.5 + 3 * 4.0 / kHeight), kGreen)) << "three pixels above the line";
  EXPECT_TRUE(near(at(0.0, 1.5), 0xFFFF00FF)) << "the marker on top";
  EXPECT_TRUE(near(at(0.0, 1.5 + 6 * 4.0 / kHeight), kBlue)) << "beside the marker";
  EXPECT_TRUE(near(at(0.6, 1.5), kBlue)) << "the marker not on top is hidden";
}

// 100 random pixels, the scene 5,000 km from the origin: each pick is a point of the scene's
// grid to the micrometre, on the surface the pixel shows, within the pick radius.
// Clipping, at UTM coordinates: a box around part of the red wall keeps only that part (drawn,
// picked), its outside keeps the rest, and a horizontal slice keeps a band of every wall; nodes
// wholly cut away are not even selected.
TEST_F(PointRendererTest, AClipBoxAndASliceKeepOnlyTheirPoints) {
  lod::NodeCache nodes(far_walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight, far_offset_);
  const Eigen::Vector3d offset(far_offset_.x, far_offset_.y, far_offset_.z);
  const std::uint32_t background = packRgba(RenderSettings{}.background);
  auto pixel = [&](const io::RgbaImage& image, double x, double z) {
    const auto [column, row] = test::frontPixel(camera, x, z, far_offset_);
    return image.pixel(column, row);
  };
  auto pickAt = [&](double x, double z) {
    const auto [column, row] = test::frontPixel(camera, x, z, far_offset_);
    return renderer.pick(column, row, 1);
  };
  const FrameStats whole = renderer.renderComplete(camera, flat());

  RenderSettings settings = flat();
  settings.clip.box = view::ClipBox{offset + Eigen::Vector3d(-2.0, 5.0, 1.5), Eigen::Vector3d(1.5, 0.5, 1.0), 0.0};
  const FrameStats boxed = renderer.renderComplete(camera, settings);
  io::RgbaImage image = renderer.readColour();
  keepForInspection(image, "clip_box");
  EXPECT_TRUE(near(pixel(image, -2.0, 1.5), 0xFF0000FF, 1));  // red, inside the box
  EXPECT_TRUE(near(pixel(image, -2.0, 0.2), background, 1));  // below it
  EXPECT_TRUE(near(pixel(image, 2.0, 1.5), background, 1));   // the green wall
  EXPECT_TRUE(near(pixel(image, 0.0, 1.5), background, 1));   // the square, in front of the box
  ASSERT_TRUE(pickAt(-2.0, 1.5).has_value());
  EXPECT_NEAR(pickAt(-2.0, 1.5)->position[1], offset.y() + 5.0, 1e-6);
  EXPECT_FALSE(pickAt(-2.0, 0.2).has_value());
  EXPECT_FALSE(pickAt(2.0, 1.5).has_value());
  EXPECT_LT(boxed.points_selected, whole.points_selected);

  settings.clip.keep_outside_box = true;
  renderer.renderComplete(camera, settings);
  image = renderer.readColour();
  EXPECT_TRUE(near(pixel(image, -2.0, 1.5), background, 1));
  EXPECT_TRUE(near(pixel(image, -2.0, 0.2), 0xFF0000FF, 1));
  EXPECT_TRUE(near(pixel(image, 2.0, 1.5), 0xFF00FF00, 1));
  EXPECT_TRUE(near(pixel(image, 0.0, 1.5), 0xFFFF0000, 1));

  settings.clip = view::horizontalSlice(offset.z() + 0.3, 0.4);
  const FrameStats sliced = renderer.renderComplete(camera, settings);
  image = renderer.readColour();
  keepForInspection(image, "clip_slice");
  EXPECT_TRUE(near(pixel(image, -2.0, 0.5), 0xFF0000FF, 1));
  EXPECT_TRUE(near(pixel(image, 2.0, 0.5), 0xFF00FF00, 1));
  EXPECT_TRUE(near(pixel(image, -2.0, 0.2), background, 1));
  EXPECT_TRUE(near(pixel(image, 2.0, 2.5), background, 1));
  EXPECT_TRUE(near(pixel(image, 0.0, 1.5), background, 1));
  EXPECT_LT(sliced.points_selected, whole.points_selected);

  settings.clip.planes.push_back({offset, Eigen::Vector3d(0.5, 0.0, 0.0)});  // not a unit normal
  EXPECT_THROW(renderer.renderComplete(camera, settings), Error);
}

// A node that fails to load in the middle of a frame (a corrupt file) makes render throw; the
// frames after it must not wait forever for the one that threw (each would wait for the frame two
// before it), and a readback still works.
TEST_F(PointRendererTest, AFrameThatThrowsDoesNotStopTheFramesAfterIt) {
  std::string bytes = plumb::test::readFile(directory_->file("walls.plumb"));
  bytes[lod::kHeaderBytes + 5] ^= 0x10;  // a byte of the root node's points: its checksum fails
  const std::string corrupt = directory_->file("corrupt.plumb");
  plumb::test::writeFile(corrupt, bytes);
  lod::NodeCache nodes(lod::Octree::open(corrupt), 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight, far_offset_);
  for (int frame = 0; frame < 4; ++frame) {
    EXPECT_THROW(renderer.render(camera, flat(), NodeLoading::kWait), Error) << "frame " << frame;
  }
  EXPECT_EQ(renderer.readColour().width, kWidth);
}

TEST_F(PointRendererTest, PickingReturnsTheVisiblePointInWorldCoordinates) {
  lod::NodeCache nodes(far_walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight, far_offset_);
  renderer.renderComplete(camera, flat());
  const io::RgbaImage image = renderer.readColour();
  std::mt19937 random(11);
  int picked = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const int x = static_cast<int>(random() % kWidth), y = static_cast<int>(random() % kHeight);
    const std::optional<PickedPoint> pick = renderer.pick(x, y, 2);
    const std::uint32_t shown = image.pixel(x, y);
    const bool shows_point = channels(shown)[0] > 200 || channels(shown)[1] > 200 || channels(shown)[2] > 200;
    if (!pick) {
      EXPECT_FALSE(shows_point) << "nothing picked at " << x << ", " << y;
      continue;
    }
    ++picked;
    EXPECT_LE((pick->pixel_x - x) * (pick->pixel_x - x) + (pick->pixel_y - y) * (pick->pixel_y - y), 4);
    const double local_x = pick->position[0] - far_offset_.x, local_y = pick->position[1] - far_offset_.y,
                 local_z = pick->position[2] - far_offset_.z;
    const double grid_x = std::round((local_x + 4.0) / test::kGridStep) * test::kGridStep - 4.0;
    const double grid_z = std::round(local_z / test::kGridStep) * test::kGridStep;
    EXPECT_NEAR(local_x, grid_x, 1e-6);
    EXPECT_NEAR(local_z, grid_z, 1e-6);
    // The nearest surface: the square (y = 3) wherever the pixel shows it, else a wall (y = 5).
    const bool blue = channels(image.pixel(pick->pixel_x, pick->pixel_y))[2] > 200;
    EXPECT_NEAR(local_y, blue ? 3.0 : 5.0, 1e-6) << "at " << x << ", " << y;
    EXPECT_NEAR(pick->depth_m, blue ? 13.0 : 15.0, 1e-3);
    const auto [column, row] = test::frontPixel(camera, local_x, local_z, far_offset_);
    EXPECT_LE(std::abs(column - pick->pixel_x), 1);
    EXPECT_LE(std::abs(row - pick->pixel_y), 1);
  }
  EXPECT_GT(picked, 60);  // most of the view shows walls
}

// Up close a point's disc covers the pixels around it, and which of the overlapping discs wins a
// pixel is a matter of depths within the noise (here, none: the lower id): picking returns the
// point whose own pixel is nearest the cursor, not the one whose disc won the cursor's pixel. The
// blue square from 400 pixels a metre, its grid 8 pixels apart and each disc 16 across.
TEST_F(PointRendererTest, PickingUpCloseReturnsThePointNearestTheCursor) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = closeUpOfTheWalls(0.75, 0.0, 1.5);
  renderer.renderComplete(camera, flat());
  const double metres_per_px = camera.ortho_height_m / camera.viewport_height_px;
  std::mt19937 random(5);
  for (int trial = 0; trial < 100; ++trial) {
    const int x = 20 + static_cast<int>(random() % 360), y = 20 + static_cast<int>(random() % 260);
    const std::optional<PickedPoint> pick = renderer.pick(x, y, 4);
    ASSERT_TRUE(pick) << x << ", " << y;
    // The square's grid point nearest the cursor (never a tie: pixel centres lie half-way
    // between pixels, the grid's points on them).
    const double cursor_x = (x + 0.5 - 0.5 * camera.viewport_width_px) * metres_per_px;
    const double cursor_z = 1.5 - (y + 0.5 - 0.5 * camera.viewport_height_px) * metres_per_px;
    EXPECT_NEAR(pick->position[0], std::round(cursor_x / test::kGridStep) * test::kGridStep, 1e-6) << x << ", " << y;
    EXPECT_NEAR(pick->position[2], std::round(cursor_z / test::kGridStep) * test::kGridStep, 1e-6) << x << ", " << y;
    EXPECT_NEAR(pick->position[1], 3.0, 1e-6);
  }
}

TEST_F(PointRendererTest, ThePointBudgetHolds) {
  lod::NodeCache nodes(walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight);
  std::uint64_t previous = 0;
  for (const std::uint64_t budget : {5'000u, 20'000u, 50'000u, 1'000'000u}) {
    RenderSettings settings = flat();
    settings.selection.point_budget = budget;
    settings.selection.max_spacing_px = 0.0;  // only the budget stops the refinement
    const FrameStats stats = renderer.renderComplete(camera, settings);
    EXPECT_LE(stats.points_drawn, budget);
    EXPECT_GE(stats.points_drawn, previous);
    EXPECT_EQ(stats.budget_reached, budget < test::wallScenePoints()) << budget;
    previous = stats.points_drawn;
  }
  EXPECT_EQ(previous, test::wallScenePoints());
  // Without a budget to stop it, the level of detail stops: a smaller view needs fewer points.
  const FrameStats small = renderer.renderComplete(test::wallSceneFront(kWidth / 4, kHeight / 4), flat());
  EXPECT_FALSE(small.budget_reached);
  EXPECT_LT(small.points_drawn, test::wallScenePoints() / 2);
}

TEST_F(PointRendererTest, ResizingAndEvictionKeepTheImageRight) {
  lod::NodeCache nodes(far_walls_, 64 << 20);
  RendererOptions options;
  options.gpu_budget_bytes = 256 << 10;  // a few nodes: every view evicts
  options.upload_ring_bytes = 1 << 20;
  PointRenderer renderer(*device_, *allocator_, nodes, options);
  const int sizes[][2] = {{64, 48}, {100, 80}, {48, 64}, {128, 96}, {64, 48}};
  for (const auto& size : sizes) {
    for (const double shift : {-2.0, 2.0}) {
      view::Camera camera = test::wallSceneFront(size[0], size[1], far_offset_);
      camera.position.x() += shift;
      camera.target.x() += shift;
      camera.ortho_height_m = 2.0;
      renderer.renderComplete(camera, flat());
      const io::RgbaImage image = renderer.readColour();
      ASSERT_EQ(image.width, size[0]);
      ASSERT_EQ(image.height, size[1]);
      // The centre shows the red wall on the left, the green one on the right.
      EXPECT_TRUE(near(image.pixel(size[0] / 2, size[1] * 3 / 4), shift < 0 ? kRed : kGreen))
          << size[0] << " x " << size[1] << ", shift " << shift;
    }
  }
  const GpuNodeCacheStats stats = renderer.gpuNodeStats();
  EXPECT_GT(stats.evictions, 0u);
  EXPECT_GT(stats.uploads, stats.nodes);
}

// Streaming never waits for disk: the first frames draw what is loaded, the parent nodes stand
// in, and once every node has arrived the picture is the one a waiting render makes.
TEST_F(PointRendererTest, StreamedFramesConvergeToTheCompleteImage) {
  const view::Camera camera = test::wallSceneFront(kWidth, kHeight, far_offset_);
  io::RgbaImage complete;
  FrameStats waited;
  {
    lod::NodeCache nodes(far_walls_, 64 << 20);
    PointRenderer renderer(*device_, *allocator_, nodes);
    waited = renderer.renderComplete(camera, flat());
    complete = renderer.readColour();
  }
  lod::NodeCache nodes(far_walls_, 64 << 20);
  PointRenderer renderer(*device_, *allocator_, nodes);
  FrameStats first = renderer.render(camera, flat());
  EXPECT_GT(first.nodes_missing, 0u);  // nothing was loaded yet
  FrameStats stats = first;
  for (int frame = 0; frame < 100'000 && !stats.complete(); ++frame) stats = renderer.render(camera, flat());
  ASSERT_TRUE(stats.complete());
  EXPECT_EQ(stats.points_drawn, waited.points_drawn);
  EXPECT_EQ(renderer.readColour().rgba, complete.rgba);
}

}  // namespace
}  // namespace plumb::render
