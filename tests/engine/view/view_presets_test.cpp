// The standard views show the whole box, and not much more.

#include "engine/view/view_presets.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "engine/view/camera_controls.h"

namespace plumb::view {
namespace {

TEST(ViewPresets, EachViewShowsTheWholeBoxAndFillsMostOfTheScreen) {
  const Eigen::Vector3d min(512000.0, 5403000.0, 250.0), max(512007.0, 5403005.0, 252.5);
  for (const auto& [name, size] : {std::pair{"top", std::pair{1920, 1080}}, std::pair{"front", std::pair{800, 800}},
                                   std::pair{"side", std::pair{600, 1000}}, std::pair{"iso", std::pair{1920, 1080}},
                                   std::pair{"iso", std::pair{500, 1000}}}) {
    const Camera camera = presetCamera(*viewPresetNamed(name), min, max, size.first, size.second);
    ASSERT_FALSE(findCameraProblem(camera)) << name;
    Eigen::Vector2d low(1e9, 1e9), high(-1e9, -1e9);
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1) ? max.x() : min.x(), (corner & 2) ? max.y() : min.y(),
                              (corner & 4) ? max.z() : min.z());
      const auto pixel = pixelOf(camera, p);
      ASSERT_TRUE(pixel) << name;
      low = low.cwiseMin(*pixel);
      high = high.cwiseMax(*pixel);
    }
    EXPECT_GE(low.x(), 0.0) << name;
    EXPECT_GE(low.y(), 0.0) << name;
    EXPECT_LE(high.x(), size.first) << name;
    EXPECT_LE(high.y(), size.second) << name;
    const double fill = std::max((high.x() - low.x()) / size.first, (high.y() - low.y()) / size.second);
    EXPECT_GT(fill, 0.6) << name << " " << size.first << " x " << size.second;
  }
  EXPECT_FALSE(viewPresetNamed("aerial"));
}

TEST(ViewPresets, TheOrthographicViewsLookAlongTheAxes) {
  const Eigen::Vector3d min(0, 0, 0), max(4, 3, 2);
  EXPECT_LT((viewDirection(presetCamera(ViewPreset::kTop, min, max, 100, 100)) - Eigen::Vector3d(0, 0, -1)).norm(),
            1e-12);
  EXPECT_LT((viewDirection(presetCamera(ViewPreset::kFront, min, max, 100, 100)) - Eigen::Vector3d(0, 1, 0)).norm(),
            1e-12);
  EXPECT_LT((viewDirection(presetCamera(ViewPreset::kSide, min, max, 100, 100)) - Eigen::Vector3d(-1, 0, 0)).norm(),
            1e-12);
}

}  // namespace
}  // namespace plumb::view
