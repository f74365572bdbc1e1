#include "engine/lod/copc_storage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "engine/core/error.h"
#include "engine/io/copc_file.h"

namespace plumb::lod {
namespace {

CellKey cellKeyOf(const io::CopcNode& node) {
  // CopcFile checked that the key lies in the cube: no negative coordinates, level <= 30.
  return {static_cast<std::uint32_t>(node.level), static_cast<std::uint32_t>(node.x),
          static_cast<std::uint32_t>(node.y), static_cast<std::uint32_t>(node.z)};
}

std::string keyText(const CellKey& key) {
  return "(" + std::to_string(key.level) + ", " + std::to_string(key.x) + ", " + std::to_string(key.y) + ", " +
         std::to_string(key.z) + ")";
}

// The order of Plumb's node index: level, then z, y, x.
bool indexOrder(const NodeInfo& a, const NodeInfo& b) {
  return std::tie(a.key.level, a.key.z, a.key.y, a.key.x) < std::tie(b.key.level, b.key.z, b.key.y, b.key.x);
}

class CopcStorage final : public OctreeStorage {
 public:
  CopcStorage(std::shared_ptr<const io::CopcFile> file, const Cube& cube) : file_(std::move(file)), cube_(cube) {}

  NodePoints load(const NodeInfo& node) const override {
    io::CopcNode chunk;
    chunk.offset = node.offset;
    chunk.bytes = static_cast<std::uint32_t>(node.bytes);
    chunk.points = node.point_count;
    std::vector<io::PointRecord> records;
    file_->readNode(chunk, records);
    NodePoints result{node.key, cube_.cellMin(node.key), {}, {}};
    result.points.reserve(records.size());
    for (const io::PointRecord& r : records) {
      // Relative to the cell's corner, so that floats keep the LAS scale's precision far from the
      // world origin (the design's rule for node positions).
      result.points.push_back({static_cast<float>(r.x - result.origin[0]), static_cast<float>(r.y - result.origin[1]),
                               static_cast<float>(r.z - result.origin[2]), r.rgb, r.intensity});
    }
    return result;
  }

  std::string format() const override { return file_->format(); }

 private:
  std::shared_ptr<const io::CopcFile> file_;
  Cube cube_;
};

// The hierarchy's nodes with points, and the point-less nodes between them and the root: a query
// descends from the root through existing nodes only, so an empty inner node must stay. Throws
// when a node's ancestor is not in the hierarchy at all.
std::vector<NodeInfo> nodeIndex(const io::CopcFile& file) {
  std::map<CellKey, NodeInfo> index;
  std::set<CellKey> named;  // every key the hierarchy lists, with points or not
  for (const io::CopcNode& node : file.nodes()) {
    const CellKey key = cellKeyOf(node);
    named.insert(key);
    if (node.points == 0) continue;
    NodeInfo& info = index[key];
    info.key = key;
    info.point_count = node.points;
    info.offset = node.offset;
    info.bytes = node.bytes;
  }
  std::vector<std::pair<CellKey, std::uint64_t>> with_points;  // key, entry offset
  for (const io::CopcNode& node : file.nodes()) {
    if (node.points > 0) with_points.emplace_back(cellKeyOf(node), node.entry_offset);
  }
  for (const auto& [key, entry_offset] : with_points) {
    for (std::optional<CellKey> parent = key.parent(); parent && !index.contains(*parent); parent = parent->parent()) {
      if (!named.contains(*parent)) {
        throw fileErrorAt(file.path(), entry_offset,
                          "the COPC node " + keyText(key) + " lies in the cell " + keyText(*parent) +
                              ", which the hierarchy does not list: a corrupt hierarchy");
      }
      index[*parent].key = *parent;
    }
  }
  std::vector<NodeInfo> nodes;
  nodes.reserve(index.size());
  for (const auto& [key, info] : index) nodes.push_back(info);
  std::sort(nodes.begin(), nodes.end(), indexOrder);
  std::map<CellKey, std::size_t> position;
  for (std::size_t i = 0; i < nodes.size(); ++i) position.emplace(nodes[i].key, i);
  for (const NodeInfo& node : nodes) {
    if (const std::optional<CellKey> parent = node.key.parent()) {
      nodes[position.at(*parent)].child_mask |= static_cast<std::uint8_t>(1u << node.key.octant());
    }
  }
  return nodes;
}

OctreeHeader headerOf(const io::CopcFile& file, const std::vector<NodeInfo>& nodes) {
  const io::LasHeader& las = file.header();
  const io::CopcInfo& info = file.info();
  OctreeHeader h;
  h.point_count = las.point_count;
  h.node_count = nodes.size();
  for (std::size_t a = 0; a < 3; ++a) h.cube.origin[a] = info.center[a] - info.halfsize;
  h.cube.size = 2.0 * info.halfsize;
  h.root_spacing = info.spacing;
  // Plumb's inner cells sample a grid of sampling_grid^3 cells (spacing = size / grid); COPC's
  // equivalent is the root's size over its spacing.
  h.sampling_grid = static_cast<std::uint32_t>(
      std::clamp(std::round(h.cube.size / info.spacing), 1.0, double{std::numeric_limits<std::uint32_t>::max()}));
  for (const NodeInfo& node : nodes) {
    h.depth = std::max(h.depth, node.key.level);
    if (node.child_mask == 0) h.leaf_max_points = std::max(h.leaf_max_points, node.point_count);
  }
  h.attributes = kHasIntensity | (las.layout.has_colour ? kHasColour : 0u);
  const Box3 cube_box{h.cube.origin,
                      {h.cube.origin[0] + h.cube.size, h.cube.origin[1] + h.cube.size, h.cube.origin[2] + h.cube.size}};
  h.bounds = las.bounds ? Box3{las.bounds->min, las.bounds->max} : cube_box;
  // The root hierarchy page plays the part of Plumb's node index; it has no checksum.
  h.index_offset = info.root_hier_offset;
  h.index_bytes = info.root_hier_size;
  h.input_files = 1;
  return h;
}

}  // namespace

OpenedOctree openCopcOctree(const std::string& path) {
  auto file = std::make_shared<const io::CopcFile>(path);
  OpenedOctree opened;
  opened.nodes = nodeIndex(*file);
  opened.header = headerOf(*file, opened.nodes);
  opened.storage = std::make_unique<CopcStorage>(std::move(file), opened.header.cube);
  return opened;
}

}  // namespace plumb::lod
