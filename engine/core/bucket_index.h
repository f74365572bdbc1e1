#pragma once
// Items 0..n-1 grouped by a key each: the items of one key, in ascending order, are one probe
// sequence of a flat open-addressing table away. Built in O(n): each item's key is found in (or
// entered into) a table sized for every item having a key of its own, which numbers the keys in
// order of their first item; a count per key and its prefix sums place each item, ascending, in
// its key's run of order(); the runs then go into a table sized for the keys. Sorting the items
// by key did the same in O(n log n) and, in the region grower, which groups the points of every
// cell it loads, was a tenth of a seed and a twentieth of a full-detail grow.
// Key: equality-comparable, default-constructible; Hash: a functor whose low bits are well spread.

#include <bit>
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

namespace plumb {

template <typename Key, typename Hash>
class BucketIndex {
 public:
  // A key's items: positions [begin, end) of order().
  struct Run {
    Key key{};
    std::uint32_t begin = 0;
    std::uint32_t end = 0;  // 0: an empty slot (a run holds at least one item)
  };

  BucketIndex() = default;

  // Groups items 0..keys.size() - 1 (at most 2^32 - 1) by keys[i].
  explicit BucketIndex(std::span<const Key> keys) {
    assert(keys.size() < 0xFFFFFFFFu && "a bucket index holds at most 2^32 - 1 items");
    if (keys.empty()) return;
    struct Numbered {
      Key key{};
      std::uint32_t number = 0;  // 0: an empty slot; otherwise the key's number + 1
    };
    std::vector<Numbered> numbering(std::bit_ceil(2 * keys.size()));
    const std::size_t numbering_mask = numbering.size() - 1;
    std::vector<std::uint32_t> number_of(keys.size());
    std::vector<Run> runs;  // per key, its run; `end` counts the items until they are placed
    for (std::uint32_t i = 0; i < keys.size(); ++i) {
      std::size_t slot = Hash{}(keys[i]) & numbering_mask;
      while (numbering[slot].number != 0 && !(numbering[slot].key == keys[i])) slot = (slot + 1) & numbering_mask;
      if (numbering[slot].number == 0) {
        runs.push_back({keys[i], 0, 0});
        numbering[slot] = {keys[i], static_cast<std::uint32_t>(runs.size())};
      }
      number_of[i] = numbering[slot].number - 1;
      ++runs[number_of[i]].end;
    }
    std::uint32_t begin = 0;
    for (Run& run : runs) {
      const std::uint32_t count = run.end;
      run.begin = run.end = begin;  // end advances as the items are placed
      begin += count;
    }
    order_.resize(keys.size());
    for (std::uint32_t i = 0; i < keys.size(); ++i) order_[runs[number_of[i]].end++] = i;
    slots_.assign(std::bit_ceil(2 * runs.size()), Run{});
    mask_ = slots_.size() - 1;
    for (const Run& run : runs) {
      std::size_t slot = Hash{}(run.key) & mask_;
      while (slots_[slot].end != 0) slot = (slot + 1) & mask_;
      slots_[slot] = run;
    }
  }

  // The run of `key`; nullptr where no item has it.
  const Run* find(const Key& key) const {
    if (slots_.empty()) return nullptr;
    for (std::size_t slot = Hash{}(key)&mask_;; slot = (slot + 1) & mask_) {
      const Run& run = slots_[slot];
      if (run.end == 0) return nullptr;
      if (run.key == key) return &run;
    }
  }

  // The items of `key`, ascending; empty when none.
  std::span<const std::uint32_t> at(const Key& key) const {
    const Run* run = find(key);
    return run == nullptr ? std::span<const std::uint32_t>() : items(*run);
  }

  std::span<const std::uint32_t> items(const Run& run) const {
    return {order_.data() + run.begin, run.end - run.begin};
  }

  // Every item, grouped by key (the groups in no particular order).
  const std::vector<std::uint32_t>& order() const { return order_; }

  // Each key's run, in no particular order.
  template <typename Visit>
  void forEachRun(Visit&& visit) const {
    for (const Run& run : slots_) {
      if (run.end != 0) visit(run);
    }
  }

 private:
  std::vector<std::uint32_t> order_;
  std::vector<Run> slots_;  // a power of two, at most half full
  std::size_t mask_ = 0;
};

}  // namespace plumb
