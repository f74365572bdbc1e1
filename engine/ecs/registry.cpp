#include "engine/ecs/registry.h"

#include "engine/ecs/history.h"

namespace plumb::ecs {

Registry::~Registry() {
  assert(history_ == nullptr && "a History outlives its Registry: destroy the History first");
}

Entity Registry::create() {
  std::uint32_t index = 0;
  if (!free_.empty()) {
    index = free_.back();
    free_.pop_back();
  } else {
    assert(slots_.size() < Entity::kNullIndex && "out of entity indices (2^32 - 1)");
    index = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  Slot& slot = slots_[index];
  slot.state = SlotState::kAlive;
  ++live_count_;
  const Entity entity{index, slot.generation};
  if (recording_) recordChange(Change{.kind = Change::Kind::kCreate, .entity = entity});
  return entity;
}

void Registry::destroy(Entity entity) {
  assert(alive(entity) && "destroy of a dead or stale entity: check alive() first");
  if (!alive(entity)) return;
  // During an edit undo must be able to bring back this very handle, so its index is not reused.
  destroyEntity(entity, recording_);
}

void Registry::destroyEntity(Entity entity, bool hold) {
  for (const std::unique_ptr<SparseSet>& pool : pools_) {
    if (pool == nullptr || !pool->contains(entity)) continue;
    if (recording_) {
      recordComponent(*pool, entity, pool->take(entity), nullptr);
    } else {
      pool->erase(entity);
    }
  }
  if (recording_) recordChange(Change{.kind = Change::Kind::kDestroy, .entity = entity});
  --live_count_;
  if (hold) {
    slots_[entity.index].state = SlotState::kHeld;
  } else {
    freeSlot(entity.index);
  }
}

bool Registry::revive(Entity entity) {
  if (entity.index >= slots_.size()) return false;
  Slot& slot = slots_[entity.index];
  if (slot.state != SlotState::kHeld || slot.generation != entity.generation) return false;
  slot.state = SlotState::kAlive;
  ++live_count_;
  return true;
}

void Registry::release(Entity entity) {
  if (entity.index >= slots_.size()) return;
  const Slot& slot = slots_[entity.index];
  if (slot.state == SlotState::kHeld && slot.generation == entity.generation) freeSlot(entity.index);
}

void Registry::freeSlot(std::uint32_t index) {
  Slot& slot = slots_[index];
  // A wrapped generation would make handles from 2^32 lifetimes ago alive again.
  if (slot.generation == Entity::kNullIndex) {
    slot.state = SlotState::kRetired;
    return;
  }
  ++slot.generation;
  slot.state = SlotState::kFree;
  free_.push_back(index);
}

void Registry::recordChange(Change&& change) {
  history_->record(std::move(change));
}

void Registry::recordComponent(const SparseSet& pool, Entity entity, std::shared_ptr<const void> before,
                               std::shared_ptr<const void> after) {
  recordChange(Change{.kind = Change::Kind::kComponent,
                      .entity = entity,
                      .component_type = pool.type(),
                      .set_component = pool.setComponentFn(),
                      .before = std::move(before),
                      .after = std::move(after)});
}

}  // namespace plumb::ecs
