#pragma once
// The storage of one component type in a Registry: a sparse set (entity index -> position in
// dense arrays of entities and values). Lookups are two array reads; removal swaps the last
// element into the hole, so the dense arrays stay packed and iteration touches no gaps, at the
// price of order: positions change on every removal.
//
// SparseSet is the type-erased half (entities, versions, removal); ComponentPool<T> adds the
// values. Registry owns one pool per component type it has seen. Not thread-safe.

#include <cassert>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/change.h"
#include "engine/ecs/component_type.h"
#include "engine/ecs/entity.h"

namespace plumb::ecs {

class SparseSet {
 public:
  SparseSet(ComponentTypeId type, Change::SetComponentFn set_component) : type_(type), set_component_(set_component) {}
  virtual ~SparseSet() = default;
  SparseSet(const SparseSet&) = delete;
  SparseSet& operator=(const SparseSet&) = delete;

  // True when `entity` (this exact generation) has a value here.
  bool contains(Entity entity) const {
    if (entity.index >= sparse_.size()) return false;
    const std::uint32_t position = sparse_[entity.index];
    return position != kAbsent && dense_[position] == entity;
  }

  std::size_t size() const { return dense_.size(); }
  bool empty() const { return dense_.empty(); }

  // The entities in dense order. Invalidated by every insertion and removal.
  std::span<const Entity> entities() const { return dense_; }

  // Bumped on every insertion, replacement, edit and removal.
  std::uint64_t version() const { return version_; }
  // Bumped on insertions and removals only: what invalidates iteration.
  std::uint64_t structureVersion() const { return structure_version_; }

  ComponentTypeId type() const { return type_; }
  Change::SetComponentFn setComponentFn() const { return set_component_; }

  // Removes `entity`'s value; it must be present.
  virtual void erase(Entity entity) = 0;
  // Removes `entity`'s value (which must be present) and returns it, moved into an immutable
  // shared copy for the history. The type must be copyable (see Registry).
  virtual std::shared_ptr<const void> take(Entity entity) = 0;

 protected:
  std::size_t position(Entity entity) const {
    assert(contains(entity) && "component absent: check has<T>() or tryGet<T>() first");
    return sparse_[entity.index];
  }

  // Appends `entity` (absent) at position size() - 1 of the dense array.
  void insertEntity(Entity entity);
  // Removes `entity` (present) by moving the last entity into its position, which it returns;
  // the caller moves its values the same way.
  std::size_t eraseEntity(Entity entity);
  void touch() { ++version_; }

 private:
  static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;

  std::vector<std::uint32_t> sparse_;  // by entity index: position in dense_, or kAbsent
  std::vector<Entity> dense_;
  std::uint64_t version_ = 0;
  std::uint64_t structure_version_ = 0;
  ComponentTypeId type_;
  Change::SetComponentFn set_component_;
};

template <class T>
class ComponentPool final : public SparseSet {
  static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "components are plain value types");
  static_assert(std::is_move_constructible_v<T> && std::is_move_assignable_v<T>,
                "removals move the last component into the hole: give the component type move construction "
                "and move assignment");

 public:
  using SparseSet::SparseSet;

  const T& get(Entity entity) const { return values_[position(entity)]; }
  const T* tryGet(Entity entity) const { return contains(entity) ? &values_[position(entity)] : nullptr; }

  // Values in the same (dense) order as entities(); invalidated like it.
  std::span<const T> values() const { return values_; }

  // Adds `value` for `entity`, which must not have one.
  const T& insert(Entity entity, T&& value) {
    values_.push_back(std::move(value));
    try {
      insertEntity(entity);
    } catch (...) {
      values_.pop_back();  // keep values_ and the dense entities the same length
      throw;
    }
    return values_.back();
  }

  // Overwrites `entity`'s value, which must be present.
  void assign(Entity entity, T&& value) {
    values_[position(entity)] = std::move(value);
    touch();
  }

  // Calls edit(T&) on `entity`'s value, which must be present.
  template <class F>
  void edit(Entity entity, F&& edit_value) {
    std::forward<F>(edit_value)(values_[position(entity)]);
    touch();
  }

  // Moves `entity`'s present value out into a shared copy without removing it (its slot is left
  // moved-from until the caller assigns or erases it).
  std::shared_ptr<const void> moveOut(Entity entity) {
    return std::make_shared<const T>(std::move(values_[position(entity)]));
  }

  void erase(Entity entity) override {
    const std::size_t hole = eraseEntity(entity);
    if (hole + 1 != values_.size()) values_[hole] = std::move(values_.back());
    values_.pop_back();
  }

  std::shared_ptr<const void> take(Entity entity) override {
    if constexpr (std::is_copy_constructible_v<T>) {
      std::shared_ptr<const void> value = moveOut(entity);
      erase(entity);
      return value;
    } else {
      assert(false && "a move-only component was removed during an edit: make it copyable or change it outside edits");
      erase(entity);
      return nullptr;
    }
  }

 private:
  std::vector<T> values_;
};

}  // namespace plumb::ecs
