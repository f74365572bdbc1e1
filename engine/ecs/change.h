#pragma once
// One recorded mutation of a Registry, type-erased so that a History holds the changes of every
// component type in one list. The values are immutable copies shared between the history and
// nothing else; applying one copies it back into the registry.

#include <cstdint>
#include <memory>

#include "engine/ecs/component_type.h"
#include "engine/ecs/entity.h"

namespace plumb::ecs {

class Registry;

struct Change {
  enum class Kind : std::uint8_t {
    kCreate,     // `entity` was created
    kDestroy,    // `entity` was destroyed; the removals of its components are recorded just before
    kComponent,  // one component of `entity` went from `before` to `after`
  };

  // Sets `entity`'s component of this change's type to a copy of *value, or removes it when value
  // is null, through the registry's public mutators (so versions are bumped). Returns false, and
  // changes nothing, when `entity` is not alive.
  using SetComponentFn = bool (*)(Registry& registry, Entity entity, const void* value);

  Kind kind = Kind::kComponent;
  Entity entity;
  ComponentTypeId component_type = 0;            // kComponent only
  SetComponentFn set_component = nullptr;        // kComponent only
  std::shared_ptr<const void> before = nullptr;  // kComponent: the value before, null when it was absent
  std::shared_ptr<const void> after = nullptr;   // kComponent: the value after, null when it is absent
};

}  // namespace plumb::ecs
