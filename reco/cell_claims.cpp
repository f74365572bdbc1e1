#include "reco/cell_claims.h"

#include <cassert>

namespace plumb::reco {

using lod::CellKey;

std::optional<CellKey> CellClaims::ownerAt(const std::array<double, 3>& p) const {
  for (std::uint32_t level = min_level_; level <= max_level_; ++level) {
    const CellKey key = cube_.cellAt(p, level);
    if (claimed_.contains(key)) return key;
  }
  return std::nullopt;
}

CellKey CellClaims::claimAt(const std::array<double, 3>& p, std::uint32_t level, std::uint32_t max_level,
                            bool& created) {
  created = false;
  if (const auto owner = ownerAt(p)) return *owner;
  // No claimed cell holds p, so no ancestor of p's cells is claimed; step down past the cells
  // that have claimed descendants (p lies beside those descendants, not in them).
  CellKey key = cube_.cellAt(p, level);
  while (below_.contains(key) && key.level < max_level) key = cube_.cellAt(p, key.level + 1);
  assert(!below_.contains(key) && "a claim at the deepest level cannot have claims below it");
  claim(key);
  created = true;
  return key;
}

void CellClaims::claim(const CellKey& key) {
  assert(!claimed_.contains(key) && !below_.contains(key) && "claims must stay disjoint across levels");
  claimed_.insert(key);
  for (auto parent = key.parent(); parent; parent = parent->parent()) {
    assert(!claimed_.contains(*parent) && "an ancestor of a new claim is claimed");
    ++below_[*parent];
  }
  min_level_ = std::min(min_level_, key.level);
  max_level_ = std::max(max_level_, key.level);
}

void CellClaims::release(const CellKey& key) {
  [[maybe_unused]] const std::size_t erased = claimed_.erase(key);
  assert(erased == 1 && "releasing a cell that is not claimed");
  for (auto parent = key.parent(); parent; parent = parent->parent()) {
    const auto it = below_.find(*parent);
    if (--it->second == 0) below_.erase(it);
  }
}

}  // namespace plumb::reco
