#include "engine/lod/octree.h"

#include <cmath>
#include <fstream>
#include <utility>

#include "engine/io/copc_file.h"
#include "engine/lod/copc_storage.h"
#include "engine/lod/plumb_storage.h"

namespace plumb::lod {

bool Octree::looksLikeOctree(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, kOctreeMagic.size()> magic{};
  in.read(magic.data(), magic.size());
  if (in.gcount() == static_cast<std::streamsize>(magic.size()) && magic == kOctreeMagic) return true;
  return io::CopcFile::looksLikeCopc(path);
}

std::shared_ptr<const Octree> Octree::open(const std::string& path) {
  OpenedOctree opened = io::CopcFile::looksLikeCopc(path) ? openCopcOctree(path) : openPlumbOctree(path);
  std::shared_ptr<Octree> tree(new Octree());
  tree->path_ = path;
  tree->storage_ = std::move(opened.storage);
  tree->header_ = opened.header;
  tree->nodes_ = std::move(opened.nodes);
  tree->lookup_.reserve(tree->nodes_.size());
  for (std::size_t i = 0; i < tree->nodes_.size(); ++i) tree->lookup_.emplace(tree->nodes_[i].key, i);
  return tree;
}

Octree::~Octree() = default;

const NodeInfo* Octree::find(const CellKey& key) const {
  const auto it = lookup_.find(key);
  return it == lookup_.end() ? nullptr : &nodes_[it->second];
}

double Octree::spacing(std::uint32_t level) const {
  return std::ldexp(header_.root_spacing, -static_cast<int>(level));
}

std::uint32_t Octree::levelForSpacing(double wanted) const {
  std::uint32_t level = 0;
  while (level < header_.depth && spacing(level) > wanted) ++level;
  return level;
}

}  // namespace plumb::lod
