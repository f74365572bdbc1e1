#pragma once
// A map from neighbour-grid cells to values that only grows (until cleared): the region
// grower's grid of the segments' points, asked 27 times per candidate point. Open addressing
// with linear probing in a flat table at most half full, values in insertion order beside it:
// a lookup is a probe or two in one array, where std::unordered_map followed a node pointer
// per cell. References to values are invalidated by the next insertion.

#include <bit>
#include <cstdint>
#include <vector>

#include "reco/point_grid.h"

namespace plumb::reco {

template <typename Value>
class GridMap {
 public:
  // The value of `key`, null when there is none.
  const Value* find(const GridKey& key) const {
    if (slots_.empty()) return nullptr;
    for (std::size_t slot = lowBitsHash(key) & mask_;; slot = (slot + 1) & mask_) {
      const Slot& s = slots_[slot];
      if (s.value == kEmpty) return nullptr;
      if (s.key == key) return &values_[s.value];
    }
  }

  // The value of `key`, default-constructed where there was none.
  Value& operator[](const GridKey& key) {
    if (2 * (values_.size() + 1) > slots_.size()) rehash(slots_.empty() ? 64 : 2 * slots_.size());
    std::size_t slot = lowBitsHash(key) & mask_;
    for (; slots_[slot].value != kEmpty; slot = (slot + 1) & mask_) {
      if (slots_[slot].key == key) return values_[slots_[slot].value];
    }
    slots_[slot] = {key, static_cast<std::uint32_t>(values_.size())};
    return values_.emplace_back();
  }

  void clear() {
    slots_.clear();
    values_.clear();
    mask_ = 0;
  }

 private:
  static constexpr std::uint32_t kEmpty = ~std::uint32_t{0};
  struct Slot {
    GridKey key{0, 0, 0};
    std::uint32_t value = kEmpty;  // index into values_
  };

  void rehash(std::size_t size) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::bit_ceil(size), Slot{});
    mask_ = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.value == kEmpty) continue;
      std::size_t slot = lowBitsHash(s.key) & mask_;
      while (slots_[slot].value != kEmpty) slot = (slot + 1) & mask_;
      slots_[slot] = s;
    }
  }

  std::vector<Slot> slots_;
  std::vector<Value> values_;
  std::size_t mask_ = 0;
};

}  // namespace plumb::reco
