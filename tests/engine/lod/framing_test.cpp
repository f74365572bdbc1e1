// The framing box: the bulk of a cloud, without its stray points, measured by the import and
// kept in the octree's header, or sampled from an older octree's shallow levels.

#include "engine/lod/framing.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <span>

#include "engine/core/error.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::lod {
namespace {

// An interior scan at UTM coordinates: 9 x 7 x 3 m of points in a box's walls, floor and
// ceiling, and two stray returns 17 m above it (as a real scan's multipath reflections).
constexpr double kX = 512000.0, kY = 5403000.0, kZ = 250.0;
constexpr std::uint64_t kStrays = 2;

io::PointRecord interiorPoint(std::uint64_t i, std::uint64_t count) {
  if (i >= count - kStrays) return test::withId(kX + 4.0 + 0.5 * double(i % 2), kY + 3.0, kZ + 20.0, i);
  const double u = test::unitHash(i, 1), v = test::unitHash(i, 2);
  switch (i % 6) {
    case 0:
      return test::withId(kX + 9.0 * u, kY + 7.0 * v, kZ, i);  // floor
    case 1:
      return test::withId(kX + 9.0 * u, kY + 7.0 * v, kZ + 3.0, i);  // ceiling
    case 2:
      return test::withId(kX, kY + 7.0 * u, kZ + 3.0 * v, i);  // walls
    case 3:
      return test::withId(kX + 9.0, kY + 7.0 * u, kZ + 3.0 * v, i);
    case 4:
      return test::withId(kX + 9.0 * u, kY, kZ + 3.0 * v, i);
    default:
      return test::withId(kX + 9.0 * u, kY + 7.0, kZ + 3.0 * v, i);
  }
}

BuildSource interior(std::uint64_t count) {
  return test::generatedSource(count, [count](std::uint64_t i) { return interiorPoint(i, count); });
}

// The room's box, within `tolerance` on every face.
void expectTheRoom(const Box3& box, double tolerance) {
  const std::array<double, 3> low{kX, kY, kZ}, high{kX + 9.0, kY + 7.0, kZ + 3.0};
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_NEAR(box.min[a], low[a], tolerance) << "axis " << a;
    EXPECT_NEAR(box.max[a], high[a], tolerance) << "axis " << a;
  }
}

std::shared_ptr<const Octree> buildInterior(const test::TempDirectory& dir, std::uint64_t count) {
  BuildOptions options;
  options.sources = {interior(count)};
  options.output = dir.file("interior.plumb");
  options.memory_mb = 256;
  options.leaf_max_points = 2000;
  buildOctree(options);
  return Octree::open(options.output);
}

void rewriteHeader(const std::string& path, const std::function<void(std::string&)>& change) {
  std::string bytes = test::readFile(path);
  change(bytes);
  const std::uint32_t crc = crc32Of(std::as_bytes(std::span(bytes)).first(kHeaderBytes - 4));
  std::memcpy(bytes.data() + kHeaderBytes - 4, &crc, 4);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(Framing, StrayPointsAreLeftOutOfTheBox) {
  constexpr std::uint64_t count = 200'000;
  Box3 bounds{{kX, kY, kZ}, {kX + 9.0, kY + 7.0, kZ + 20.0}};
  AxisHistograms histograms(bounds);
  for (std::uint64_t i = 0; i < count; ++i) {
    const io::PointRecord p = interiorPoint(i, count);
    histograms.add({p.x, p.y, p.z});
  }
  // A bin is 20 m / 4096 = 5 mm high; the quantiles cut at most 200 points of a face's 33,000.
  expectTheRoom(histograms.framingBox(), 0.02);
}

TEST(Framing, ASmallCloudOrNoPointsIsFramedOnItsBounds) {
  const Box3 bounds{{0.0, 0.0, 0.0}, {10.0, 10.0, 30.0}};
  AxisHistograms histograms(bounds);
  const Box3 empty = histograms.framingBox();
  EXPECT_EQ(empty.min, bounds.min);
  EXPECT_EQ(empty.max, bounds.max);
  // 999 points: a quantile of 0.1 % leaves none out, so the two strays at 30 m stay in.
  for (int i = 0; i < 997; ++i) histograms.add({0.01 * i, 0.01 * i, 0.003 * i});
  histograms.add({10.0, 10.0, 30.0});
  histograms.add({0.0, 0.0, 0.0});
  const Box3 box = histograms.framingBox();
  EXPECT_EQ(box.min, bounds.min);
  EXPECT_EQ(box.max, bounds.max);
  // A flat cloud keeps its zero height.
  AxisHistograms flat({{0.0, 0.0, 5.0}, {1.0, 1.0, 5.0}});
  for (int i = 0; i < 5000; ++i) flat.add({0.0002 * i, 0.0002 * i, 5.0});
  EXPECT_EQ(flat.framingBox().min[2], 5.0);
  EXPECT_EQ(flat.framingBox().max[2], 5.0);
}

TEST(Framing, PartsMergeToTheWhole) {
  const Box3 bounds{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
  AxisHistograms whole(bounds), first(bounds), second(bounds);
  for (std::uint64_t i = 0; i < 20'000; ++i) {
    const std::array<double, 3> p{test::unitHash(i, 1), test::unitHash(i, 2), test::unitHash(i, 3) * 0.5};
    whole.add(p);
    (i % 3 == 0 ? first : second).add(p);
  }
  first.merge(second);
  EXPECT_EQ(first.count(), whole.count());
  EXPECT_EQ(first.framingBox().min, whole.framingBox().min);
  EXPECT_EQ(first.framingBox().max, whole.framingBox().max);
  EXPECT_LT(whole.framingBox().max[2], 0.51);
}

TEST(Framing, TheImportKeepsItInTheHeader) {
  test::TempDirectory dir;
  const auto octree = buildInterior(dir, 100'000);
  const OctreeHeader& header = octree->header();
  EXPECT_EQ(octree->format(), "Plumb octree 3");
  EXPECT_NEAR(header.bounds.max[2], kZ + 20.0, 1e-6) << "the bounds keep the strays";
  ASSERT_TRUE(header.framing.has_value());
  expectTheRoom(*header.framing, 0.02);
  EXPECT_EQ(framingBox(*octree).max, header.framing->max);
}

// Octrees of format 2 and COPC files have no framing box: it comes from their shallow levels,
// whose points thin the cloud evenly.
TEST(Framing, AnOlderOctreeIsFramedFromItsShallowLevels) {
  test::TempDirectory dir;
  const std::string path = dir.file("interior.plumb");
  buildInterior(dir, 400'000);
  rewriteHeader(path, [](std::string& bytes) {
    const std::uint32_t version = 2;
    std::memcpy(bytes.data() + 8, &version, 4);
    std::memset(bytes.data() + 192, 0, 48);  // version 2 wrote zeros there
  });
  const auto octree = Octree::open(path);
  EXPECT_EQ(octree->format(), "Plumb octree 2");
  EXPECT_FALSE(octree->header().framing.has_value());
  // A sample's quantiles are coarser: within 15 cm of the room (a bin of 5 mm, 0.1 % of a
  // sample that holds each face by its area).
  expectTheRoom(framingBox(*octree), 0.15);
}

TEST(Framing, ABoxOutsideTheBoundsIsACorruptHeader) {
  test::TempDirectory dir;
  const std::string path = dir.file("interior.plumb");
  buildInterior(dir, 20'000);
  rewriteHeader(path, [](std::string& bytes) {
    const double beyond = kZ + 25.0;
    std::memcpy(bytes.data() + 192 + 40, &beyond, 8);  // the framing box's maximum z
  });
  try {
    Octree::open(path);
    FAIL() << "a framing box above the bounds was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("framing box does not lie inside the bounds"), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("192"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace plumb::lod
