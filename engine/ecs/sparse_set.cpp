#include "engine/ecs/sparse_set.h"

namespace plumb::ecs {

void SparseSet::insertEntity(Entity entity) {
  assert(entity.index != Entity::kNullIndex && "inserting kNullEntity: create the entity through the Registry");
  if (entity.index >= sparse_.size()) sparse_.resize(std::size_t{entity.index} + 1, kAbsent);
  assert(sparse_[entity.index] == kAbsent && "component already present: use replace or emplaceOrReplace");
  dense_.push_back(entity);
  sparse_[entity.index] = static_cast<std::uint32_t>(dense_.size() - 1);
  ++version_;
  ++structure_version_;
}

std::size_t SparseSet::eraseEntity(Entity entity) {
  const std::size_t hole = position(entity);
  const Entity last = dense_.back();
  dense_[hole] = last;
  sparse_[last.index] = static_cast<std::uint32_t>(hole);
  dense_.pop_back();
  sparse_[entity.index] = kAbsent;  // after the move: `last` may be `entity` itself
  ++version_;
  ++structure_version_;
  return hole;
}

}  // namespace plumb::ecs
