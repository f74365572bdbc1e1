#pragma once
// Iteration over the entities that have every one of a set of component types, read-only.
// A View walks the smallest of its pools and looks each entity up in the others, so its cost
// follows the rarest component, not the number of entities.
//
//   for (auto [entity, segment, outline] : registry.view<Segment, Outline>()) { ... }
//   registry.view<Segment, Outline>().each([](Entity e, const Segment& s, const Outline& o) { ... });
//
// While iterating, components of the viewed types must not be added or removed (emplace, remove,
// destroy of an entity that has one, undo, redo): removal moves the last element into the hole and
// would skip or repeat entities. Debug builds assert at the next step. Collect the entities first
// and change them after the loop. replace and patch are allowed (they change values in place), as
// is any change to other component types. Order is the lead pool's dense order: unspecified and
// changed by every removal.

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <tuple>
#include <type_traits>
#include <utility>

#include "engine/ecs/entity.h"
#include "engine/ecs/sparse_set.h"

namespace plumb::ecs {

template <class... Ts>
class View {
  static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");

 public:
  // `pools` may be null: a type no entity ever had makes the view empty.
  explicit View(const ComponentPool<Ts>*... pools) : pools_{pools...} {
    const std::array<const SparseSet*, sizeof...(Ts)> sets{pools...};
    for (std::size_t i = 0; i < sets.size(); ++i) {
      sets_[i] = sets[i];
      if (sets[i] == nullptr) {
        lead_ = nullptr;
        break;
      }
      if (lead_ == nullptr || sets[i]->size() < lead_->size()) lead_ = sets[i];
    }
    for (std::size_t i = 0; i < sets_.size(); ++i) structure_[i] = sets_[i] ? sets_[i]->structureVersion() : 0;
  }

  class Iterator {
   public:
    using value_type = std::tuple<Entity, const Ts&...>;
    using difference_type = std::ptrdiff_t;

    Iterator() = default;

    value_type operator*() const { return view_->row(view_->lead_->entities()[position_]); }

    Iterator& operator++() {
      view_->assertUnchanged();
      ++position_;
      skipIncomplete();
      return *this;
    }
    void operator++(int) { ++*this; }

    // Compared against the end of the lead pool as it is now, so a misused loop in a release build
    // stops instead of reading past the end.
    friend bool operator==(const Iterator& it, std::default_sentinel_t) { return it.atEnd(); }

   private:
    friend class View;
    explicit Iterator(const View* view) : view_(view) { skipIncomplete(); }

    bool atEnd() const { return view_ == nullptr || view_->lead_ == nullptr || position_ >= view_->lead_->size(); }

    void skipIncomplete() {
      while (!atEnd() && !view_->containsAll(view_->lead_->entities()[position_])) ++position_;
    }

    const View* view_ = nullptr;
    std::size_t position_ = 0;
  };

  // Yields std::tuple<Entity, const Ts&...>; the references are invalidated like the pools'. Iterators
  // point into the View: keep it alive while iterating (a range-for over registry.view<...>() does).
  Iterator begin() const { return Iterator(this); }
  std::default_sentinel_t end() const { return std::default_sentinel; }

  // Calls fn(Entity, const Ts&...) for each entity that has all of Ts.
  template <class F>
  void each(F&& fn) const {
    static_assert(std::is_invocable_v<F&, Entity, const Ts&...>, "each wants fn(Entity, const Ts&...)");
    for (Iterator it = begin(); it != end(); ++it) std::apply(fn, *it);
  }

  // An upper bound on the number of entities visited: the size of the smallest pool.
  std::size_t sizeHint() const { return lead_ ? lead_->size() : 0; }

 private:
  bool containsAll(Entity entity) const {
    for (const SparseSet* set : sets_) {
      if (set != lead_ && !set->contains(entity)) return false;
    }
    return true;
  }

  std::tuple<Entity, const Ts&...> row(Entity entity) const { return rowAt(entity, std::index_sequence_for<Ts...>{}); }
  template <std::size_t... Is>
  std::tuple<Entity, const Ts&...> rowAt(Entity entity, std::index_sequence<Is...>) const {
    return std::tuple<Entity, const Ts&...>(entity, std::get<Is>(pools_)->get(entity)...);
  }

  void assertUnchanged() const {
    for (std::size_t i = 0; i < sets_.size(); ++i) {
      assert((sets_[i] == nullptr || sets_[i]->structureVersion() == structure_[i]) &&
             "a component of a viewed type was added or removed inside the loop: collect the entities and change "
             "them after it");
    }
  }

  std::tuple<const ComponentPool<Ts>*...> pools_;
  std::array<const SparseSet*, sizeof...(Ts)> sets_{};
  std::array<std::uint64_t, sizeof...(Ts)> structure_{};
  const SparseSet* lead_ = nullptr;  // the smallest pool; null when a pool is missing
};

}  // namespace plumb::ecs
