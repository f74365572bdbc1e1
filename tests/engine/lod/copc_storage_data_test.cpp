// COPC files opened in place as octrees (copc_storage.h), on the reference files of
// ../shared/data/formats/copc (skipped when absent): the octree's nodes hold exactly the points
// the sequential LAZ reader gives, its levels have the info VLR's spacing, and a malformed
// hierarchy or chunk is refused with the file and the byte offset.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "engine/core/error.h"
#include "engine/io/copc_file.h"
#include "engine/io/file_source.h"
#include "engine/io/point_reader.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "tests/support/shared_data.h"
#include "tests/support/temp_directory.h"

namespace plumb::lod {
namespace {

const char* const kCopcFiles[] = {"copc/1.2-with-color.copc.laz",   "copc/autzen.copc.laz",
                                  "copc/autzen_clip_4326.copc.laz", "copc/autzen_clip_native.copc.laz",
                                  "copc/lone-star.copc.laz",        "copc/simple_with_page.copc.laz"};

// A point as the LAS file stores it: integer coordinates (X = (x - offset) / scale), intensity,
// colour. Comparing these compares positions to within the file's own precision.
using StoredPoint =
    std::tuple<std::int64_t, std::int64_t, std::int64_t, std::uint16_t, std::uint16_t, std::uint16_t, std::uint16_t>;

StoredPoint stored(const std::array<double, 3>& p, std::uint16_t intensity, const std::array<std::uint16_t, 3>& rgb,
                   const io::LasHeader& las) {
  std::array<std::int64_t, 3> integer{};
  for (std::size_t a = 0; a < 3; ++a) integer[a] = std::llround((p[a] - las.offset[a]) / las.scale[a]);
  return {integer[0], integer[1], integer[2], intensity, rgb[0], rgb[1], rgb[2]};
}

std::vector<StoredPoint> sequentialPoints(const std::string& path, const io::LasHeader& las) {
  std::vector<StoredPoint> points;
  const auto reader = io::openLas(path);
  io::PointBatch batch;
  while (reader->read(batch, 65536)) {
    for (const io::PointRecord& r : batch.points) points.push_back(stored({r.x, r.y, r.z}, r.intensity, r.rgb, las));
  }
  std::sort(points.begin(), points.end());
  return points;
}

// Every reference file opens as an octree without an import. The union of its nodes' chunks is,
// point for point, what reading the file in order gives; and each node of the octree holds its
// chunk's points in the same order, positions to within the float precision of a position
// relative to the node's cell (the LAS scale can be finer: 1e-7 m in autzen_clip_native).
TEST(CopcOctree, EveryReferenceFileHoldsTheSequentialReadersPoints) {
  for (const char* name : kCopcFiles) {
    PLUMB_REQUIRE_FORMAT_FILE(path, name);
    SCOPED_TRACE(name);
    ASSERT_TRUE(Octree::looksLikeOctree(path));
    const auto octree = Octree::open(path);
    const io::CopcFile copc(path);
    const io::LasHeader& las = copc.header();

    std::vector<StoredPoint> chunk_points;
    std::uint64_t nodes_with_points = 0;
    std::vector<io::PointRecord> records;
    for (const io::CopcNode& node : copc.nodes()) {
      if (node.points == 0) continue;
      ++nodes_with_points;
      copc.readNode(node, records);
      ASSERT_EQ(records.size(), node.points);
      const NodeInfo* info = octree->find({static_cast<std::uint32_t>(node.level), static_cast<std::uint32_t>(node.x),
                                           static_cast<std::uint32_t>(node.y), static_cast<std::uint32_t>(node.z)});
      ASSERT_NE(info, nullptr);
      ASSERT_EQ(info->point_count, node.points);
      const NodePoints loaded = octree->load(*info);
      ASSERT_EQ(loaded.size(), records.size());
      const double tolerance = octree->cube().cellSize(info->key.level) * std::ldexp(1.0, -22);
      for (std::size_t i = 0; i < records.size(); ++i) {
        const io::PointRecord& r = records[i];
        const std::array<double, 3> p = loaded.position(i);
        ASSERT_NEAR(p[0], r.x, tolerance);
        ASSERT_NEAR(p[1], r.y, tolerance);
        ASSERT_NEAR(p[2], r.z, tolerance);
        ASSERT_EQ(loaded.points[i].rgb, r.rgb);
        ASSERT_EQ(loaded.points[i].intensity, r.intensity);
        chunk_points.push_back(stored({r.x, r.y, r.z}, r.intensity, r.rgb, las));
      }
    }
    std::uint64_t octree_nodes_with_points = 0, octree_points = 0;
    for (const NodeInfo& node : octree->nodes()) {
      octree_nodes_with_points += node.point_count > 0 ? 1 : 0;
      octree_points += node.point_count;
    }
    EXPECT_EQ(octree_nodes_with_points, nodes_with_points);
    EXPECT_EQ(octree_points, las.point_count);
    EXPECT_EQ(octree->header().point_count, las.point_count);
    EXPECT_EQ(octree->header().node_count, octree->nodes().size());
    std::sort(chunk_points.begin(), chunk_points.end());
    EXPECT_TRUE(chunk_points == sequentialPoints(path, las)) << "the chunks' points differ from the file's";
  }
}

// The octree's index is the hierarchy as Plumb's queries expect it: sorted by level, z, y, x,
// every node's parent present, child masks naming exactly the children present.
TEST(CopcOctree, NodesFormOneHierarchy) {
  for (const char* name : kCopcFiles) {
    PLUMB_REQUIRE_FORMAT_FILE(path, name);
    SCOPED_TRACE(name);
    const auto octree = Octree::open(path);
    const std::vector<NodeInfo>& nodes = octree->nodes();
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const CellKey& key = nodes[i].key;
      if (i > 0) {
        const CellKey& before = nodes[i - 1].key;
        EXPECT_LT(std::tie(before.level, before.z, before.y, before.x), std::tie(key.level, key.z, key.y, key.x));
      }
      if (const auto parent = key.parent()) {
        EXPECT_NE(octree->find(*parent), nullptr);
      }
      for (int o = 0; o < 8; ++o) {
        EXPECT_EQ(((nodes[i].child_mask >> o) & 1) != 0, octree->find(key.child(o)) != nullptr);
      }
      EXPECT_LE(key.level, octree->header().depth);
    }
  }
}

// The cube is the info VLR's (center +- halfsize) and level L's spacing is its spacing / 2^L.
TEST(CopcOctree, CubeAndSpacingComeFromTheInfoRecord) {
  PLUMB_REQUIRE_FORMAT_FILE(path, "copc/lone-star.copc.laz");
  const auto octree = Octree::open(path);
  const io::CopcInfo info = io::CopcFile(path).info();
  for (std::size_t a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(octree->cube().origin[a], info.center[a] - info.halfsize);
  EXPECT_DOUBLE_EQ(octree->cube().size, 2.0 * info.halfsize);
  for (std::uint32_t level = 0; level <= octree->header().depth + 2; ++level) {
    EXPECT_DOUBLE_EQ(octree->spacing(level), info.spacing / std::pow(2.0, level)) << "level " << level;
  }
  EXPECT_GT(octree->header().depth, 0u);
  EXPECT_EQ(octree->header().input_files, 1u);
  EXPECT_NE(octree->format().find("COPC 1.0"), std::string::npos) << octree->format();
}

// A LAS or LAZ file without the COPC info VLR is a point file to import, not an octree.
TEST(CopcOctree, PlainLasAndLazAreNotOctrees) {
  PLUMB_REQUIRE_FORMAT_FILE(las, "las/simple.las");
  EXPECT_FALSE(Octree::looksLikeOctree(las));
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(las).parent_path().parent_path() / "laz")) {
    if (entry.path().extension() == ".laz") {
      EXPECT_FALSE(Octree::looksLikeOctree(entry.path().string())) << entry.path();
    }
  }
}

// Nodes load through the node cache as a Plumb octree's do, each once, counting the bytes read.
TEST(CopcOctree, NodesLoadThroughTheNodeCache) {
  PLUMB_REQUIRE_FORMAT_FILE(path, "copc/lone-star.copc.laz");
  NodeCache cache(Octree::open(path), 256 << 20);
  const NodeInfo& root = cache.octree().nodes().front();
  ASSERT_NE(cache.get(root.key), nullptr);
  ASSERT_NE(cache.get(root.key), nullptr);
  EXPECT_EQ(cache.stats().misses, 1u);
  EXPECT_EQ(cache.stats().hits, 1u);
  EXPECT_EQ(cache.stats().bytes_read, root.bytes);
}

// --- Malformed files: a small reference file copied and damaged in one place. ---------------

class MalformedCopc : public ::testing::Test {
 protected:
  void SetUp() override {
    original_ = test::sharedFormatFile("copc/simple_with_page.copc.laz");
    if (original_.empty()) PLUMB_SHARED_DATA_MISSING("copc/simple_with_page.copc.laz not found in ../shared/data/formats");
    std::ifstream in(original_, std::ios::binary);
    bytes_.assign(std::istreambuf_iterator<char>(in), {});
    copc_ = std::make_unique<io::CopcFile>(original_);
    io::FileSource source(original_);
    info_at_ = io::findLasVlr(source, copc_->header(), "copc", 1)->offset;
  }

  template <typename T>
  void put(std::uint64_t offset, T value) {
    std::memcpy(bytes_.data() + offset, &value, sizeof(T));  // little-endian, as the test machine
  }

  // Writes the damaged bytes and returns the message open() throws, or "" when it opens.
  std::string openError() {
    path_ = dir_.write("damaged.copc.laz", bytes_);
    try {
      Octree::open(path_);
    } catch (const Error& error) {
      return error.what();
    }
    return {};
  }

  // The entry of the node with points at `level` (the first one the hierarchy lists).
  const io::CopcNode& nodeAtLevel(std::int32_t level) const {
    for (const io::CopcNode& node : copc_->nodes()) {
      if (node.level == level && node.points > 0) return node;
    }
    throw std::runtime_error("no node at that level");
  }

  // The root page's entry that points at a child page (point count -1), or 0.
  std::uint64_t childPagePointer() const {
    for (std::uint64_t e = 0; e < copc_->info().root_hier_size / 32; ++e) {
      const std::uint64_t entry = copc_->info().root_hier_offset + 32 * e;
      std::int32_t count = 0;
      std::memcpy(&count, bytes_.data() + entry + 28, 4);
      if (count == -1) return entry;
    }
    return 0;
  }

  static std::string at(std::uint64_t offset) { return "at byte " + std::to_string(offset); }

  test::TempDirectory dir_;
  std::string original_, path_;
  std::string bytes_;
  std::unique_ptr<io::CopcFile> copc_;
  std::uint64_t info_at_ = 0;
};

TEST_F(MalformedCopc, RootPageBeyondTheEnd) {
  put<std::uint64_t>(info_at_ + 40, bytes_.size() + 1000);
  const std::string error = openError();
  EXPECT_NE(error.find(path_), std::string::npos) << error;
  EXPECT_NE(error.find(at(info_at_ + 40)), std::string::npos) << error;
  EXPECT_NE(error.find("outside the file"), std::string::npos) << error;
}

TEST_F(MalformedCopc, ChildPageBeyondTheEnd) {
  const std::uint64_t pointer_at = childPagePointer();
  ASSERT_NE(pointer_at, 0u) << "the file has a child page";
  put<std::uint64_t>(pointer_at + 16, bytes_.size() - 8);
  const std::string error = openError();
  EXPECT_NE(error.find(at(pointer_at)), std::string::npos) << error;
  EXPECT_NE(error.find("outside the file"), std::string::npos) << error;
}

// A child page that points back at the root page: a loop, refused instead of followed forever.
TEST_F(MalformedCopc, PageLoop) {
  const std::uint64_t pointer_at = childPagePointer();
  ASSERT_NE(pointer_at, 0u) << "the file has a child page";
  put<std::uint64_t>(pointer_at + 16, copc_->info().root_hier_offset);
  put<std::int32_t>(pointer_at + 24, static_cast<std::int32_t>(copc_->info().root_hier_size));
  const std::string error = openError();
  EXPECT_NE(error.find(at(pointer_at)), std::string::npos) << error;
  EXPECT_NE(error.find("listed twice"), std::string::npos) << error;
}

TEST_F(MalformedCopc, KeyOutsideTheCube) {
  const io::CopcNode& node = nodeAtLevel(1);
  put<std::int32_t>(node.entry_offset + 4, 2);  // x = 2 at level 1: past the cube's two cells
  const std::string error = openError();
  EXPECT_NE(error.find(at(node.entry_offset)), std::string::npos) << error;
  EXPECT_NE(error.find("outside the octree's cube"), std::string::npos) << error;
}

TEST_F(MalformedCopc, KeyWithoutAParent) {
  const io::CopcNode& node = nodeAtLevel(1);
  put<std::int32_t>(node.entry_offset, 9);  // (9, x, y, z): nothing between it and the root
  const std::string error = openError();
  EXPECT_NE(error.find(at(node.entry_offset)), std::string::npos) << error;
  EXPECT_NE(error.find("which the hierarchy does not list"), std::string::npos) << error;
}

TEST_F(MalformedCopc, AbsurdPointCount) {
  const io::CopcNode& node = nodeAtLevel(0);
  put<std::int32_t>(node.entry_offset + 28, 2'000'000'000);
  const std::string error = openError();
  EXPECT_NE(error.find(at(node.entry_offset)), std::string::npos) << error;
  EXPECT_NE(error.find("more than the file's"), std::string::npos) << error;
}

TEST_F(MalformedCopc, PointCountsThatDisagreeWithTheHeader) {
  const io::CopcNode& node = nodeAtLevel(0);
  put<std::int32_t>(node.entry_offset + 28, static_cast<std::int32_t>(node.points - 1));
  const std::string error = openError();
  EXPECT_NE(error.find("the header says"), std::string::npos) << error;
}

TEST_F(MalformedCopc, TruncatedChunkFailsWhenItsNodeLoads) {
  // The hierarchy is intact; the root's chunk is cut to a third of its bytes.
  const io::CopcNode& node = nodeAtLevel(0);
  put<std::int32_t>(node.entry_offset + 24, static_cast<std::int32_t>(node.bytes / 3));
  ASSERT_EQ(openError(), "");
  const auto octree = Octree::open(path_);
  try {
    octree->load(*octree->find({0, 0, 0, 0}));
    FAIL() << "a truncated chunk loads";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path_), std::string::npos) << message;
    EXPECT_NE(message.find("at byte "), std::string::npos) << message;
    EXPECT_NE(message.find("from byte " + std::to_string(node.offset)), std::string::npos) << message;
  }
}

TEST_F(MalformedCopc, TruncatedFile) {
  bytes_.resize(bytes_.size() / 2);
  const std::string error = openError();
  EXPECT_NE(error.find(path_), std::string::npos) << error;
  EXPECT_NE(error.find("at byte "), std::string::npos) << error;
}

}  // namespace
}  // namespace plumb::lod
