#pragma once
// The entity-component registry: entities are handles (entity.h), components are plain values
// stored per type in sparse sets (sparse_set.h). Any copyable, movable struct can be a component;
// an entity has at most one of each type.
//
// Every change goes through emplace, replace, emplaceOrReplace, getOrEmplace, patch, remove,
// create and destroy. There is deliberately no mutable get: these calls are the only writers, so
// each one can bump the type's version() (what a renderer polls) and, while an edit of the attached
// History is open, be recorded for undo (history.h).
//
// Component types that are recorded must be copy-constructible: the history keeps copies of the
// values before and after. Move-only types work outside edits; changing one inside an edit asserts.
//
// Not thread-safe: one thread owns a registry (the app's main thread); views and references
// returned by get are invalidated by insertions and removals of the same component type.

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/change.h"
#include "engine/ecs/component_type.h"
#include "engine/ecs/entity.h"
#include "engine/ecs/sparse_set.h"
#include "engine/ecs/view.h"

namespace plumb::ecs {

class History;
class Registry;

namespace detail {
// Change::SetComponentFn for component type T.
template <class T>
bool setComponentState(Registry& registry, Entity entity, const void* value);

// An immutable copy of `value` for the history.
template <class T>
std::shared_ptr<const void> recordedCopy(const T& value) {
  if constexpr (std::is_copy_constructible_v<T>) {
    return std::make_shared<const T>(value);
  } else {
    assert(false && "a move-only component was changed during an edit: make it copyable or change it outside edits");
    return nullptr;
  }
}
}  // namespace detail

class Registry {
 public:
  Registry() = default;
  // The History attached to this registry must be destroyed first (asserted).
  ~Registry();
  // Not copyable or movable: an attached History and views point at it.
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // --- Entities ---------------------------------------------------------------------------------

  // A new entity with no components. Reuses the index of a destroyed entity with the next
  // generation, so handles of the destroyed one stay dead. At most 2^32 - 1 indices (asserted).
  Entity create();

  // Removes all of `entity`'s components, then the entity; it must be alive (asserted). Handles to
  // it become stale. During an edit the index is kept out of reuse so that undo can bring the same
  // handle back.
  void destroy(Entity entity);

  // True for a handle returned by create() whose entity has not been destroyed since. False for
  // kNullEntity and for stale handles (their slot was reused or is free).
  bool alive(Entity entity) const {
    return entity.index < slots_.size() && slots_[entity.index].state == SlotState::kAlive &&
           slots_[entity.index].generation == entity.generation;
  }

  // The number of live entities.
  std::size_t size() const { return live_count_; }

  // --- Components -------------------------------------------------------------------------------
  // Mutators take `entity` alive (asserted) and bump version<T>().

  // Adds `value` as `entity`'s T; it must not have one (asserted: use replace or emplaceOrReplace).
  // The reference is read-only and valid until the next insertion or removal of a T.
  template <class T>
  const T& emplace(Entity entity, T value);

  // Overwrites `entity`'s T, which must be present (asserted: use emplace or emplaceOrReplace).
  template <class T>
  void replace(Entity entity, T value);

  // emplace when absent, replace when present.
  template <class T>
  const T& emplaceOrReplace(Entity entity, T value);

  // `entity`'s T, after emplacing `value` when it had none (`value` is discarded when it had one).
  template <class T>
  const T& getOrEmplace(Entity entity, T value = T{});

  // Removes `entity`'s T. Returns false, and changes nothing, when it had none.
  template <class T>
  bool remove(Entity entity);

  // Calls edit(T&) on `entity`'s T, which must be present (asserted). During an edit it edits a
  // copy and replaces the value with it, so the change is recorded; outside it edits in place.
  template <class T, class F>
  void patch(Entity entity, F&& edit);

  // True when `entity` is alive and has a T.
  template <class T>
  bool has(Entity entity) const {
    const ComponentPool<T>* pool = find<T>();
    return pool != nullptr && pool->contains(entity);
  }

  // `entity`'s T, which must be present (asserted). Valid until the next insertion or removal of
  // a T; read-only, change it through replace or patch.
  template <class T>
  const T& get(Entity entity) const {
    const ComponentPool<T>* pool = find<T>();
    assert(pool != nullptr && pool->contains(entity) &&
           "get of an absent component: check has<T>() or use tryGet<T>(); the entity may be stale");
    return pool->get(entity);
  }

  // `entity`'s T, or null when it has none or is not alive. Valid like get's reference.
  template <class T>
  const T* tryGet(Entity entity) const {
    const ComponentPool<T>* pool = find<T>();
    return pool != nullptr ? pool->tryGet(entity) : nullptr;
  }

  // The number of entities with a T.
  template <class T>
  std::size_t count() const {
    const ComponentPool<T>* pool = find<T>();
    return pool != nullptr ? pool->size() : 0;
  }

  // A counter bumped by every change of any T (insertion, replacement, patch, removal, destroy of
  // an entity that had one, undo and redo). 0 until the first. Compare with the value seen last
  // frame to learn "segments changed" without looking at them.
  template <class T>
  std::uint64_t version() const {
    const ComponentPool<T>* pool = find<T>();
    return pool != nullptr ? pool->version() : 0;
  }

  // The entities with all of Ts, with their values (view.h: no insertions or removals of Ts while
  // iterating).
  template <class... Ts>
  View<Ts...> view() const {
    return View<Ts...>(find<Ts>()...);
  }

  // True while an edit of the attached History is open: mutations are being recorded.
  bool recording() const { return recording_; }

 private:
  friend class History;

  enum class SlotState : std::uint8_t {
    kFree,     // in free_, generation is the next one to hand out
    kAlive,    // generation is the live entity's
    kHeld,     // destroyed during an edit or by undo; only the history may revive or release it
    kRetired,  // the generation would wrap: never reused
  };
  struct Slot {
    std::uint32_t generation = 0;
    SlotState state = SlotState::kFree;
  };

  template <class T>
  const ComponentPool<T>* find() const {
    const ComponentTypeId type = componentTypeId<T>();
    return type < pools_.size() ? static_cast<const ComponentPool<T>*>(pools_[type].get()) : nullptr;
  }
  template <class T>
  ComponentPool<T>* find() {
    return const_cast<ComponentPool<T>*>(std::as_const(*this).find<T>());
  }
  template <class T>
  ComponentPool<T>& assure();

  void assertMutable(Entity entity) const {
    assert(alive(entity) && "changing a component of a dead or stale entity: check alive() first");
    (void)entity;
  }

  // destroy without the alive check; `hold` keeps the index for the history instead of freeing it.
  void destroyEntity(Entity entity, bool hold);
  // For History: makes the held `entity` alive again. False when its slot is not held with that
  // generation (the entity was destroyed outside an edit and its index reused).
  bool revive(Entity entity);
  // For History: frees the index of the held `entity` for reuse; nothing when it is not held.
  void release(Entity entity);
  void freeSlot(std::uint32_t index);

  void recordChange(Change&& change);
  void recordComponent(const SparseSet& pool, Entity entity, std::shared_ptr<const void> before,
                       std::shared_ptr<const void> after);

  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;  // indices of kFree slots, reused last-in first-out
  std::size_t live_count_ = 0;
  std::vector<std::unique_ptr<SparseSet>> pools_;  // by ComponentTypeId; null for types not seen
  History* history_ = nullptr;                     // set by History's constructor
  bool recording_ = false;                         // an edit of history_ is open
};

// --- Templates ----------------------------------------------------------------------------------

template <class T>
ComponentPool<T>& Registry::assure() {
  const ComponentTypeId type = componentTypeId<T>();
  if (type >= pools_.size()) pools_.resize(type + 1);
  if (!pools_[type]) pools_[type] = std::make_unique<ComponentPool<T>>(type, &detail::setComponentState<T>);
  return static_cast<ComponentPool<T>&>(*pools_[type]);
}

template <class T>
const T& Registry::emplace(Entity entity, T value) {
  assertMutable(entity);
  ComponentPool<T>& pool = assure<T>();
  assert(!pool.contains(entity) && "emplace of a component the entity has: use replace or emplaceOrReplace");
  const T& stored = pool.insert(entity, std::move(value));
  if (recording_) recordComponent(pool, entity, nullptr, detail::recordedCopy(stored));
  return stored;
}

template <class T>
void Registry::replace(Entity entity, T value) {
  assertMutable(entity);
  ComponentPool<T>* pool = find<T>();
  assert(pool != nullptr && pool->contains(entity) &&
         "replace of a component the entity lacks: use emplace or emplaceOrReplace");
  if (!recording_) {
    pool->assign(entity, std::move(value));
    return;
  }
  // The old value is about to be overwritten: move it into the history rather than copy it.
  std::shared_ptr<const void> before;
  if constexpr (std::is_copy_constructible_v<T>) before = pool->moveOut(entity);
  pool->assign(entity, std::move(value));
  recordComponent(*pool, entity, std::move(before), detail::recordedCopy(pool->get(entity)));
}

template <class T>
const T& Registry::emplaceOrReplace(Entity entity, T value) {
  if (!has<T>(entity)) return emplace<T>(entity, std::move(value));
  replace<T>(entity, std::move(value));
  return get<T>(entity);
}

template <class T>
const T& Registry::getOrEmplace(Entity entity, T value) {
  if (const T* present = tryGet<T>(entity)) return *present;
  return emplace<T>(entity, std::move(value));
}

template <class T>
bool Registry::remove(Entity entity) {
  assertMutable(entity);
  ComponentPool<T>* pool = find<T>();
  if (pool == nullptr || !pool->contains(entity)) return false;
  if (recording_) {
    recordComponent(*pool, entity, pool->take(entity), nullptr);
  } else {
    pool->erase(entity);
  }
  return true;
}

template <class T, class F>
void Registry::patch(Entity entity, F&& edit) {
  static_assert(std::is_invocable_v<F&&, T&>, "patch wants edit(T&)");
  assertMutable(entity);
  ComponentPool<T>* pool = find<T>();
  assert(pool != nullptr && pool->contains(entity) && "patch of a component the entity lacks: emplace it first");
  if (!recording_) {
    pool->edit(entity, std::forward<F>(edit));
    return;
  }
  if constexpr (std::is_copy_constructible_v<T>) {
    T copy = pool->get(entity);
    std::forward<F>(edit)(copy);
    replace<T>(entity, std::move(copy));
  } else {
    assert(false && "a move-only component was patched during an edit: make it copyable or patch it outside edits");
  }
}

template <class T>
bool detail::setComponentState(Registry& registry, Entity entity, const void* value) {
  if (!registry.alive(entity)) return false;
  if (value == nullptr) {
    registry.remove<T>(entity);
    return true;
  }
  if constexpr (std::is_copy_constructible_v<T>) {
    registry.emplaceOrReplace<T>(entity, *static_cast<const T*>(value));
    return true;
  } else {
    return false;
  }
}

}  // namespace plumb::ecs
