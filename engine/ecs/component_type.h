#pragma once
// Component type ids without RTTI: each component type gets the next number of one process-wide
// counter the first time it is asked for. Ids are small and dense (0, 1, 2, ... in order of first
// use), so a registry indexes its pools by them directly. They differ between runs: never store them.

#include <cstddef>
#include <type_traits>

namespace plumb::ecs {

using ComponentTypeId = std::size_t;

namespace detail {
// The next unused id. Thread-safe.
ComponentTypeId nextComponentTypeId();
}  // namespace detail

// The id of component type T (cv and reference qualifiers ignored); the same for the whole
// process. Thread-safe (a function-local static).
template <class T>
ComponentTypeId componentTypeId() {
  if constexpr (!std::is_same_v<T, std::remove_cvref_t<T>>) {
    return componentTypeId<std::remove_cvref_t<T>>();
  } else {
    static const ComponentTypeId id = detail::nextComponentTypeId();
    return id;
  }
}

}  // namespace plumb::ecs
