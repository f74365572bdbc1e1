#pragma once
// An entity handle: an index into the registry's slots plus the generation of that slot when the
// entity was created. Destroying an entity bumps its slot's generation before the index is reused,
// so a handle kept past its entity's destruction never names the newcomer (Registry::alive is false).

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace plumb::ecs {

struct Entity {
  // The index no live entity has; kNullEntity carries it.
  static constexpr std::uint32_t kNullIndex = 0xFFFFFFFFu;

  std::uint32_t index = kNullIndex;
  std::uint32_t generation = kNullIndex;

  // Both fields in one number, generation in the high half, for JSON dumps and logs; kNullEntity
  // is 2^64 - 1. Round-trips through fromId.
  constexpr std::uint64_t id() const { return (std::uint64_t{generation} << 32) | index; }
  static constexpr Entity fromId(std::uint64_t id) {
    return Entity{static_cast<std::uint32_t>(id & 0xFFFFFFFFu), static_cast<std::uint32_t>(id >> 32)};
  }

  // Ordered by index, then generation: handles can key std::map and std::set.
  friend constexpr auto operator<=>(const Entity&, const Entity&) = default;
};

// The handle of no entity; a default-constructed Entity equals it. Never alive in any registry.
inline constexpr Entity kNullEntity{};

}  // namespace plumb::ecs

template <>
struct std::hash<plumb::ecs::Entity> {
  std::size_t operator()(plumb::ecs::Entity entity) const noexcept { return std::hash<std::uint64_t>{}(entity.id()); }
};
