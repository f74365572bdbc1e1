#pragma once
// Which octree cell owns each region of space during a grow (paper section 3.6).
//
// The adaptive resolution works on cells of several levels at once: a sparse stretch of wall at
// a finer level than its neighbours, say. Claims keep those cells disjoint, so that every place
// is grown from exactly one cell, at one level: a cell is claimed only where neither an ancestor
// nor a descendant of it is. Replacing a cell by its children, or by its parent, releases the
// old claims before taking the new ones.
//
// A value type, used by one grower on one thread.

#include <array>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "engine/lod/cell_key.h"
#include "engine/lod/cube.h"

namespace plumb::reco {

class CellClaims {
 public:
  explicit CellClaims(const lod::Cube& cube) : cube_(cube) {}

  // The claimed cell that contains `p`, if any. O(levels in use).
  std::optional<lod::CellKey> ownerAt(const std::array<double, 3>& p) const;

  // The claimed cell that contains `p`; where none does, claims the cell of `level` there, or
  // the finest-needed smaller one when cells inside it are claimed already. `created` tells
  // whether the claim is new.
  lod::CellKey claimAt(const std::array<double, 3>& p, std::uint32_t level, std::uint32_t max_level, bool& created);

  bool claimed(const lod::CellKey& key) const { return claimed_.contains(key); }
  // Whether a descendant of `key` is claimed.
  bool claimedBelow(const lod::CellKey& key) const { return below_.contains(key); }

  // Claims `key`. It must not be claimed, nor any of its ancestors or descendants.
  void claim(const lod::CellKey& key);
  // Releases a claimed cell.
  void release(const lod::CellKey& key);

  std::size_t size() const { return claimed_.size(); }
  const std::unordered_set<lod::CellKey, lod::CellKeyHash>& cells() const { return claimed_; }

 private:
  lod::Cube cube_;
  std::unordered_set<lod::CellKey, lod::CellKeyHash> claimed_;
  // For each ancestor of a claimed cell, how many claimed cells lie below it.
  std::unordered_map<lod::CellKey, std::uint32_t, lod::CellKeyHash> below_;
  std::uint32_t min_level_ = ~0u;  // the range of levels ever claimed, for ownerAt
  std::uint32_t max_level_ = 0;
};

}  // namespace plumb::reco
