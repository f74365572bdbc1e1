// Building, reading and checking octrees.

#include "engine/lod/octree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <span>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "engine/core/error.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::lod {
namespace {

// A room-like cloud at UTM coordinates: a 20 x 12 m floor and a 20 x 3 m wall, jittered, each
// point tagged with its index as id.
io::PointRecord roomPoint(std::uint64_t i) {
  const double u = test::unitHash(i, 1), v = test::unitHash(i, 2);
  if (i % 4 == 0) return test::withId(512000.0 + 20.0 * u, 5403012.0, 250.0 + 3.0 * v, i);  // wall
  return test::withId(512000.0 + 20.0 * u, 5403000.0 + 12.0 * v, 250.0 + 0.001 * test::unitHash(i, 3), i);
}

struct Built {
  BuildReport report;
  std::shared_ptr<const Octree> octree;
};

Built build(const test::TempDirectory& dir, std::vector<BuildSource> sources, std::size_t memory_mb = 256,
            std::uint32_t leaf_max = 2000) {
  BuildOptions options;
  options.sources = std::move(sources);
  options.output = dir.file("cloud.plumb");
  options.memory_mb = memory_mb;
  options.leaf_max_points = leaf_max;
  Built built{buildOctree(options), nullptr};
  built.octree = Octree::open(options.output);
  return built;
}

// Every point, by id, with its position read back.
std::unordered_map<std::uint64_t, std::array<double, 3>> pointsById(const Octree& octree) {
  std::unordered_map<std::uint64_t, std::array<double, 3>> points;
  for (const NodeInfo& node : octree.nodes()) {
    const NodePoints loaded = octree.load(node);
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      const auto id = test::idOf(loaded.points[i].rgb, loaded.points[i].intensity);
      EXPECT_TRUE(points.emplace(id, loaded.position(i)).second) << "point " << id << " stored twice";
    }
  }
  return points;
}

void expectEveryPointKeptToTheMillimetre(const Octree& octree, std::uint64_t count) {
  const auto points = pointsById(octree);
  ASSERT_EQ(points.size(), count);
  double worst = 0.0;
  for (const auto& [id, p] : points) {
    const io::PointRecord truth = roomPoint(id);
    worst = std::max({worst, std::abs(p[0] - truth.x), std::abs(p[1] - truth.y), std::abs(p[2] - truth.z)});
  }
  EXPECT_LT(worst, 1e-5) << "positions must keep far better than millimetres at UTM coordinates";
}

TEST(Octree, RoundTripKeepsEveryPointAndAttributeOnce) {
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(200'000, roomPoint)});
  EXPECT_EQ(built.report.points, 200'000u);
  EXPECT_EQ(built.octree->header().point_count, 200'000u);
  EXPECT_GT(built.octree->header().depth, 1u);
  expectEveryPointKeptToTheMillimetre(*built.octree, 200'000);
}

TEST(Octree, ManySmallChunksGiveTheSamePoints) {
  // 64 MiB forces many chunks and the levels above them to be built from the chunk roots.
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(300'000, roomPoint)}, 64, 500);
  EXPECT_GT(built.report.chunks, 4u);
  expectEveryPointKeptToTheMillimetre(*built.octree, 300'000);
}

TEST(Octree, NodesFormOneHierarchy) {
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(200'000, roomPoint)}, 64, 500);
  const Octree& octree = *built.octree;
  ASSERT_NE(octree.find(CellKey{}), nullptr);
  std::uint64_t points = 0;
  for (const NodeInfo& node : octree.nodes()) {
    points += node.point_count;
    if (node.key.level > 0) {
      EXPECT_NE(octree.find(*node.key.parent()), nullptr) << "orphan node";
    }
    for (int o = 0; o < 8; ++o) {
      EXPECT_EQ(((node.child_mask >> o) & 1) != 0, octree.find(node.key.child(o)) != nullptr);
    }
    if (node.child_mask == 0) {
      EXPECT_GT(node.point_count, 0u) << "an empty leaf";
    }
    // Points lie in their node's cell.
    const NodePoints loaded = octree.load(node);
    const Box3 box = octree.cube().cellBox(node.key);
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      const auto p = loaded.position(i);
      for (std::size_t a = 0; a < 3; ++a) {
        ASSERT_GE(p[a], box.min[a] - 1e-6);
        ASSERT_LE(p[a], box.max[a] + 1e-6);
      }
    }
  }
  EXPECT_EQ(points, octree.header().point_count);
}

// Mean distance from each point to its nearest other point, on the floor (z near 250), within
// the central 10 x 6 m.
double meanNearestNeighbour(const std::vector<std::array<double, 3>>& points, double cell) {
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  auto key = [&](double x, double y) {
    return (static_cast<std::int64_t>(std::floor(x / cell)) << 32) ^ static_cast<std::int64_t>(std::floor(y / cell));
  };
  for (std::size_t i = 0; i < points.size(); ++i) grid[key(points[i][0], points[i][1])].push_back(i);
  double sum = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (p[0] < 512005 || p[0] > 512015 || p[1] < 5403003 || p[1] > 5403009) continue;
    double best = INFINITY;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find(key(p[0] + dx * cell, p[1] + dy * cell));
        if (it == grid.end()) continue;
        for (std::size_t j : it->second) {
          if (j != i) best = std::min(best, std::hypot(points[j][0] - p[0], points[j][1] - p[1]));
        }
      }
    }
    if (std::isfinite(best)) {
      sum += best;
      ++counted;
    }
  }
  return sum / counted;
}

TEST(Octree, SpacingHalvesWithEachLevel) {
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(400'000, roomPoint)}, 256, 1000);
  const Octree& octree = *built.octree;
  std::vector<std::array<double, 3>> levels_so_far;
  double previous = 0.0;
  for (std::uint32_t level = 0; level <= 2; ++level) {
    for (const NodeInfo& node : octree.nodes()) {
      if (node.key.level != level) continue;
      const NodePoints loaded = octree.load(node);
      for (std::size_t i = 0; i < loaded.size(); ++i) {
        if (loaded.position(i)[2] < 250.01) levels_so_far.push_back(loaded.position(i));
      }
    }
    const double spacing = octree.spacing(level);
    const double measured = meanNearestNeighbour(levels_so_far, 2.0 * spacing);
    RecordProperty("level_" + std::to_string(level) + "_spacing_mm", std::to_string(measured * 1e3));
    std::printf("level %u: nominal spacing %.4f m, mean nearest neighbour %.4f m, %zu points\n", level, spacing,
                measured, levels_so_far.size());
    EXPECT_GT(measured, 0.5 * spacing) << "level " << level;
    EXPECT_LT(measured, 1.5 * spacing) << "level " << level;
    if (level > 0) {
      EXPECT_NEAR(measured / previous, 0.5, 0.1) << "level " << level;
    }
    previous = measured;
  }
}

TEST(Octree, SeveralInputsMergeAndSkippedPointsAreCounted) {
  test::TempDirectory dir;
  auto second = [](std::uint64_t i) {
    io::PointRecord p = roomPoint(1'000'000 + i);
    if (i % 10 == 0) p.x = NAN;
    return p;
  };
  const Built built = build(dir, {test::generatedSource(50'000, roomPoint), test::generatedSource(20'000, second)});
  EXPECT_EQ(built.report.points, 50'000u + 18'000u);
  EXPECT_EQ(built.octree->header().skipped_non_finite, 2'000u);
  EXPECT_EQ(built.octree->header().input_files, 2u);
}

// A cloud merged from several scans keeps each point's: an input of two scans (as an E57 file
// reports them) and a plain file make scans 0 and 1 of the first and 2 of the second, named
// after their inputs, and every point reads back with the scan it came from.
TEST(Octree, EachPointKeepsTheIndexOfItsScan) {
  test::TempDirectory dir;
  const auto two_scans = [](std::uint64_t i) {
    io::PointRecord p = roomPoint(i);
    p.scan = static_cast<std::uint16_t>(i % 3 == 0 ? 1 : 0);
    return p;
  };
  const Built built = build(dir, {test::generatedSource(40'000, two_scans, "site.e57", {"north", "south"}),
                                  test::generatedSource(
                                      30'000, [](std::uint64_t i) { return roomPoint(1'000'000 + i); }, "extra.ply")});
  const OctreeHeader& h = built.octree->header();
  EXPECT_EQ(h.attributes & kHasScanIndex, kHasScanIndex);
  EXPECT_EQ(h.scans, (std::vector<std::string>{"site.e57: north", "site.e57: south", "extra.ply"}));
  EXPECT_EQ(built.report.scans, h.scans);
  EXPECT_EQ(built.octree->format(), "Plumb octree 3");
  std::array<std::uint64_t, 3> per_scan{};
  for (const NodeInfo& node : built.octree->nodes()) {
    const NodePoints loaded = built.octree->load(node);
    ASSERT_EQ(loaded.scans.size(), loaded.size());
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      const std::uint64_t id = test::idOf(loaded.points[i].rgb, loaded.points[i].intensity);
      const std::uint16_t expected = id >= 1'000'000 ? 2 : id % 3 == 0 ? 1 : 0;
      ASSERT_EQ(loaded.scans[i], expected) << "point " << id;
      ++per_scan[expected];
    }
  }
  EXPECT_EQ(per_scan, (std::array<std::uint64_t, 3>{26'666, 13'334, 30'000}));
}

// One scan has nothing to tell apart: no scan index, no table, the points as before.
TEST(Octree, ACloudOfOneScanKeepsNoScanIndex) {
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(20'000, roomPoint, "one.ply")});
  EXPECT_EQ(built.octree->header().attributes & kHasScanIndex, 0u);
  EXPECT_TRUE(built.octree->header().scans.empty());
  EXPECT_EQ(built.report.file_bytes, kHeaderBytes + 20'000 * kPointBytes + built.report.nodes * kIndexEntryBytes);
  for (const NodeInfo& node : built.octree->nodes()) EXPECT_TRUE(built.octree->load(node).scans.empty());
}

// Octrees of format 1 (written before scans existed) open and read as they did.
TEST(Octree, AVersionOneFileStillOpens) {
  test::TempDirectory dir;
  const Built built = build(dir, {test::generatedSource(20'000, roomPoint)});
  const std::string path = dir.file("cloud.plumb");
  std::string bytes = test::readFile(path);
  const std::uint32_t version = 1;
  std::memcpy(bytes.data() + 8, &version, 4);
  const std::uint32_t crc = crc32Of(std::as_bytes(std::span(bytes)).first(kHeaderBytes - 4));
  std::memcpy(bytes.data() + kHeaderBytes - 4, &crc, 4);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  const auto old = Octree::open(path);
  EXPECT_EQ(old->format(), "Plumb octree 1");
  expectEveryPointKeptToTheMillimetre(*old, 20'000);
}

// The nodes of an octree with each node's point ids, to compare two builds.
std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>, std::vector<std::uint64_t>>
nodeContents(const Octree& octree) {
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>, std::vector<std::uint64_t>> nodes;
  for (const NodeInfo& node : octree.nodes()) {
    const NodePoints loaded = octree.load(node);
    auto& ids = nodes[{node.key.level, node.key.x, node.key.y, node.key.z}];
    for (const PackedPoint& p : loaded.points) ids.push_back(test::idOf(p.rgb, p.intensity));
    std::sort(ids.begin(), ids.end());
  }
  return nodes;
}

// The room's points from a reader whose header states `bounds`, as a LAS file's does.
BuildSource roomWithDeclaredBounds(std::uint64_t count, const io::Bounds& bounds) {
  return {"declared.las", [count, bounds] {
            auto reader = std::make_unique<test::GeneratedReader>(count, roomPoint);
            reader->declareBounds(bounds);
            return reader;
          }};
}

// Inputs whose headers state their bounds are read twice instead of three times, into the same
// octree; bounds the points do not fit, or loose ones, cost the pass back and change nothing.
TEST(Octree, BoundsFromTheHeadersSaveAPassAndChangeNothing) {
  constexpr std::uint64_t count = 30'000;
  test::TempDirectory dir;
  const Built read = build(dir, {test::generatedSource(count, roomPoint)});
  EXPECT_FALSE(read.report.bounds_from_headers);
  const Box3 bounds = read.octree->header().bounds;
  const auto reference = nodeContents(*read.octree);

  struct Case {
    const char* what;
    io::Bounds declared;
    bool wrong;
  };
  io::Bounds tight{bounds.min, bounds.max}, inside = tight, loose = tight;
  inside.max[2] -= 1.0;  // the wall's top lies above it
  for (std::size_t a = 0; a < 3; ++a) loose.max[a] += 100.0;
  for (const Case& c : {Case{"exact", tight, false}, Case{"too small", inside, true}, Case{"loose", loose, true}}) {
    const Built declared = build(dir, {roomWithDeclaredBounds(count, c.declared)});
    EXPECT_TRUE(declared.report.bounds_from_headers) << c.what;
    EXPECT_EQ(declared.report.header_bounds_wrong, c.wrong) << c.what;
    const OctreeHeader& header = declared.octree->header();
    EXPECT_EQ(header.point_count, count) << c.what;
    EXPECT_EQ(header.bounds.min, bounds.min) << c.what;
    EXPECT_EQ(header.bounds.max, bounds.max) << c.what;
    EXPECT_NEAR(header.cube.size, read.octree->header().cube.size, 1e-6 * header.cube.size) << c.what;
    ASSERT_TRUE(header.framing.has_value()) << c.what;
    EXPECT_EQ(header.framing->min, read.octree->header().framing->min) << c.what;
    EXPECT_EQ(header.framing->max, read.octree->header().framing->max) << c.what;
    EXPECT_TRUE(nodeContents(*declared.octree) == reference) << c.what << ": other nodes or points";
  }
  // Bounds whose extent a double cannot hold are no bounds: the points are read for them.
  const io::Bounds absurd{{-1e308, -1e308, -1e308}, {1e308, 1e308, 1e308}};
  const Built read_again = build(dir, {roomWithDeclaredBounds(count, absurd)});
  EXPECT_FALSE(read_again.report.bounds_from_headers);
  EXPECT_TRUE(nodeContents(*read_again.octree) == reference);
}

TEST(Octree, ASinglePointAndDuplicatesBuild) {
  test::TempDirectory dir;
  const Built one = build(dir, {test::generatedSource(1, roomPoint)});
  EXPECT_EQ(one.octree->header().point_count, 1u);
  const Built same = build(
      dir,
      {test::generatedSource(30'000, [](std::uint64_t i) { return test::withId(512000.5, 5403000.5, 250.5, i); })});
  EXPECT_EQ(same.octree->header().point_count, 30'000u);
  EXPECT_EQ(pointsById(*same.octree).size(), 30'000u);
}

// The message names the inputs (an empty E57 or LAS said "the input holds no points", naming
// nothing) and counts the points left out for want of a position.
TEST(Octree, NoPointsIsAnErrorThatNamesTheInputsAndLeavesNothing) {
  test::TempDirectory dir;
  const auto message = [&](std::vector<BuildSource> sources) {
    BuildOptions options;
    options.sources = std::move(sources);
    options.output = dir.file("empty.plumb");
    try {
      buildOctree(options);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const auto invalid = [](std::uint64_t) { return io::PointRecord{NAN, 0, 0, {}, 0}; };
  EXPECT_EQ(message({test::generatedSource(10, invalid, "scan.e57")}),
            "'scan.e57': the file holds no points with a valid position (10 points without one were skipped)");
  EXPECT_EQ(dir.entryCount(), 0u);
  EXPECT_EQ(message({test::generatedSource(0, invalid, "a.las"), test::generatedSource(0, invalid, "b.ply")}),
            "none of the 2 inputs holds a point: 'a.las', 'b.ply'");
  EXPECT_EQ(dir.entryCount(), 0u);
}

class CorruptOctree : public ::testing::Test {
 protected:
  void SetUp() override {
    built_ = build(dir_, {test::generatedSource(20'000, roomPoint)});
    path_ = dir_.file("cloud.plumb");
    bytes_ = test::readFile(path_);
  }
  void rewrite(const std::string& bytes) {
    built_.octree.reset();
    std::ofstream(path_, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  std::string openError() {
    try {
      const auto octree = Octree::open(path_);
      for (const NodeInfo& node : octree->nodes()) octree->load(node);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }

  test::TempDirectory dir_;
  Built built_;
  std::string path_;
  std::string bytes_;
};

TEST_F(CorruptOctree, AFlippedPointByteIsReportedAtItsNode) {
  std::string bytes = bytes_;
  bytes[kHeaderBytes + 5] ^= 0x10;
  rewrite(bytes);
  const std::string message = openError();
  EXPECT_NE(message.find("corrupt (checksum mismatch)"), std::string::npos) << message;
  EXPECT_NE(message.find(path_), std::string::npos) << message;
}

TEST_F(CorruptOctree, HeaderIndexTruncationAndVersionAreChecked) {
  std::string header = bytes_;
  header[40] ^= 0x01;
  rewrite(header);
  EXPECT_NE(openError().find("header is corrupt"), std::string::npos) << openError();

  std::string index = bytes_;
  index[index.size() - 3] ^= 0x01;
  rewrite(index);
  EXPECT_NE(openError().find("index is corrupt"), std::string::npos) << openError();

  rewrite(bytes_.substr(0, bytes_.size() - 100));
  EXPECT_NE(openError().find("outside the file"), std::string::npos) << openError();

  std::string newer = bytes_;
  newer[8] = 9;
  rewrite(newer);
  EXPECT_NE(openError().find("newer than this Plumb"), std::string::npos) << openError();

  rewrite("PLY\n");
  EXPECT_NE(openError().find("not a Plumb octree"), std::string::npos) << openError();
  rewrite(bytes_.substr(0, 100));
  EXPECT_NE(openError().find("shorter than an octree header"), std::string::npos) << openError();
  rewrite(std::string(300, 'x'));
  EXPECT_NE(openError().find("not a Plumb octree"), std::string::npos) << openError();
}

// A damaged scan table, or a header whose scan flag and count disagree, is reported as such.
TEST(CorruptScans, ABadScanTableOrFlagIsReported) {
  test::TempDirectory dir;
  const auto two = [](std::uint64_t i) {
    io::PointRecord p = roomPoint(i);
    p.scan = static_cast<std::uint16_t>(i % 2);
    return p;
  };
  build(dir, {test::generatedSource(5'000, two, "pair.e57", {"a", "b"})});
  const std::string path = dir.file("cloud.plumb");
  const std::string bytes = test::readFile(path);
  auto errorOf = [&](const std::string& changed) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(changed.data(), static_cast<std::streamsize>(changed.size()));
    try {
      Octree::open(path);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  std::string table = bytes;
  table[table.size() - 1] ^= 0x20;  // the table ends the file: the last byte of "pair.e57: b"
  EXPECT_NE(errorOf(table).find("scan table is corrupt"), std::string::npos) << errorOf(table);

  OctreeHeader header = decodeHeader(std::as_bytes(std::span(bytes)).first<kHeaderBytes>(), path);
  header.attributes &= ~std::uint32_t{kHasScanIndex};
  std::string flag = bytes;
  const auto encoded = encodeHeader(header);
  std::memcpy(flag.data(), encoded.data(), kHeaderBytes);
  EXPECT_NE(errorOf(flag).find("scan index flag and the scan count disagree"), std::string::npos) << errorOf(flag);
  EXPECT_NE(errorOf(flag).find(path), std::string::npos);
}

// Found by the fuzz target (tests/fuzz/corpus/octree/node_count_wraps.plumb): a node count whose
// index size wraps to the real one, 2^62 + 1 entries times 40 bytes = 40 mod 2^64, under valid
// checksums, once passed the header check and threw std::length_error from reserve().
TEST_F(CorruptOctree, ANodeCountWhoseIndexSizeWrapsIsReported) {
  const auto header_bytes = std::as_bytes(std::span(bytes_)).first<kHeaderBytes>();
  OctreeHeader header = decodeHeader(header_bytes, path_);
  header.node_count += std::uint64_t{1} << 62;  // times 40: a multiple of 2^64 more
  const auto wrapped = encodeHeader(header);
  std::string bytes = bytes_;
  std::memcpy(bytes.data(), wrapped.data(), kHeaderBytes);
  rewrite(bytes);
  EXPECT_NE(openError().find("node index lies outside the file"), std::string::npos) << openError();
}

}  // namespace
}  // namespace plumb::lod
