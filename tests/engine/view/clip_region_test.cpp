// The clip region on the host: what keeps() keeps, and cutsAway() never skipping a cell that
// holds a kept point (node selection relies on it).

#include "engine/view/clip_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/core/error.h"

namespace plumb::view {
namespace {

TEST(ClipRegion, ABoxTurnedAboutTheVerticalKeepsItsInsideOrOutside) {
  ClipRegion region;
  region.box = ClipBox{{10.0, 20.0, 1.0}, {2.0, 0.5, 1.0}, M_PI / 2.0};  // long along y once turned
  EXPECT_TRUE(region.keeps({10.0, 21.9, 1.0}));
  EXPECT_FALSE(region.keeps({11.9, 20.0, 1.0}));
  EXPECT_FALSE(region.keeps({10.0, 20.0, 2.1}));
  region.keep_outside_box = true;
  EXPECT_FALSE(region.keeps({10.0, 21.9, 1.0}));
  EXPECT_TRUE(region.keeps({11.9, 20.0, 1.0}));
}

TEST(ClipRegion, ASliceKeepsItsBandAndPlanesTheirSide) {
  const ClipRegion slice = horizontalSlice(1.15, 0.1);
  EXPECT_TRUE(slice.keeps({5.0, -3.0, 1.2}));
  EXPECT_FALSE(slice.keeps({5.0, -3.0, 1.1}));
  EXPECT_FALSE(slice.keeps({5.0, -3.0, 1.3}));
  const ClipRegion slab = slabAbout({0.0, 5.0, 0.0}, {0.0, -2.0, 0.0}, 0.2);
  EXPECT_TRUE(slab.keeps({3.0, 5.09, 7.0}));
  EXPECT_FALSE(slab.keeps({3.0, 5.11, 7.0}));
  EXPECT_FALSE(slab.keeps({3.0, 4.89, 7.0}));
}

// The settings a user states compose into one region: a slice and a slab about a wall keep the
// band of the wall within both.
TEST(ClipRegion, SettingsComposeTheirParts) {
  ClipSettings settings;
  EXPECT_FALSE(settings.active());
  settings.slice = true;
  settings.slice_bottom_z = 1.0;
  settings.slice_thickness = 0.5;
  settings.slab = ClipSlab{{0.0, 5.0, 0.0}, {0.0, 1.0, 0.0}, 0.2};
  EXPECT_TRUE(settings.active());
  const ClipRegion region = settings.region();
  EXPECT_EQ(region.planes.size(), 4u);
  EXPECT_TRUE(region.keeps({3.0, 5.05, 1.2}));
  EXPECT_FALSE(region.keeps({3.0, 5.15, 1.2}));  // beyond the slab
  EXPECT_FALSE(region.keeps({3.0, 5.05, 1.6}));  // above the slice
}

TEST(ClipRegion, ACellCutAwayHoldsNoKeptPoint) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0), unit(0.0, 1.0);
  int cut = 0;
  for (int trial = 0; trial < 300; ++trial) {
    ClipRegion region;
    region.box = ClipBox{{coordinate(random), coordinate(random), coordinate(random)},
                         {0.2 + unit(random), 0.2 + unit(random), 0.2 + unit(random)},
                         6.0 * unit(random)};
    region.keep_outside_box = trial % 3 == 0;
    if (trial % 2 == 0) {
      region.planes.push_back({{coordinate(random), coordinate(random), coordinate(random)},
                               Eigen::Vector3d(coordinate(random), coordinate(random), 0.5).normalized()});
    }
    const Eigen::Vector3d low(coordinate(random), coordinate(random), coordinate(random));
    const double size = 0.1 + 2.0 * unit(random);
    if (!region.cutsAway(low, low + Eigen::Vector3d::Constant(size))) continue;
    ++cut;
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d p = low + size * Eigen::Vector3d(unit(random), unit(random), unit(random));
      ASSERT_FALSE(region.keeps(p)) << "trial " << trial;
    }
  }
  EXPECT_GT(cut, 30) << "the trials should cut some cells away";
}

TEST(ClipRegion, RegionsTheRendererCannotTakeAreRefused) {
  ClipRegion flat;
  flat.box = ClipBox{{0, 0, 0}, {1.0, 0.0, 1.0}, 0.0};
  EXPECT_THROW(checkClipRegion(flat, "test"), Error);
  ClipRegion many;
  for (int i = 0; i < 27; ++i) many.planes.push_back({});
  EXPECT_NO_THROW(checkClipRegion(many, "test"));  // 27 planes alone fit
  many.box = ClipBox{};
  EXPECT_THROW(checkClipRegion(many, "test"), Error);  // with the box's six: 33
  ClipRegion tilted;
  tilted.planes.push_back({{0, 0, 0}, {0.0, 0.0, 2.0}});
  EXPECT_THROW(checkClipRegion(tilted, "test"), Error);
}

}  // namespace
}  // namespace plumb::view
