#include "engine/ecs/component_type.h"

#include <atomic>

namespace plumb::ecs::detail {

ComponentTypeId nextComponentTypeId() {
  static std::atomic<ComponentTypeId> next{0};
  return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace plumb::ecs::detail
