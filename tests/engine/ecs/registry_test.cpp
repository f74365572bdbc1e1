#include "engine/ecs/registry.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <unordered_set>
#include <vector>

namespace plumb::ecs {
namespace {

struct Position {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Position&) const = default;
};

// Owns heap memory, so a wrong move during swap-removal shows up under ASan.
struct Label {
  std::string text;
  bool operator==(const Label&) const = default;
};

struct Selected {};

TEST(Entity, IdRoundTripsAndNullIsDefault) {
  const Entity entity{7, 3};
  EXPECT_EQ(entity.id(), (std::uint64_t{3} << 32) | 7u);
  EXPECT_EQ(Entity::fromId(entity.id()), entity);
  EXPECT_EQ(Entity{}, kNullEntity);
  EXPECT_EQ(kNullEntity.id(), ~std::uint64_t{0});
  EXPECT_NE((Entity{7, 4}), entity);
  EXPECT_LT((Entity{1, 9}), (Entity{2, 0}));

  std::unordered_set<Entity> set{entity, Entity{7, 4}, entity};
  EXPECT_EQ(set.size(), 2u);
  EXPECT_EQ(std::hash<Entity>{}(entity), std::hash<std::uint64_t>{}(entity.id()));
}

TEST(Registry, CreateDestroyAndGenerationReuse) {
  Registry registry;
  EXPECT_FALSE(registry.alive(kNullEntity));
  const Entity a = registry.create();
  const Entity b = registry.create();
  const Entity c = registry.create();
  EXPECT_EQ(a, (Entity{0, 0}));
  EXPECT_EQ(b, (Entity{1, 0}));
  EXPECT_EQ(c, (Entity{2, 0}));
  EXPECT_EQ(registry.size(), 3u);

  registry.destroy(b);
  EXPECT_FALSE(registry.alive(b));
  EXPECT_TRUE(registry.alive(a));
  EXPECT_TRUE(registry.alive(c));
  EXPECT_EQ(registry.size(), 2u);

  // The freed index comes back with the next generation; the old handle stays dead.
  const Entity d = registry.create();
  EXPECT_EQ(d, (Entity{1, 1}));
  EXPECT_TRUE(registry.alive(d));
  EXPECT_FALSE(registry.alive(b));
  EXPECT_EQ(registry.size(), 3u);

  registry.destroy(d);
  const Entity e = registry.create();
  EXPECT_EQ(e, (Entity{1, 2}));
  EXPECT_FALSE(registry.alive(b));
  EXPECT_FALSE(registry.alive(d));
  EXPECT_FALSE(registry.alive(Entity{3, 0}));  // never created
}

TEST(Registry, StaleHandlesSeeNoComponents) {
  Registry registry;
  const Entity old = registry.create();
  registry.emplace(old, Position{1, 2});
  registry.destroy(old);
  EXPECT_EQ(registry.count<Position>(), 0u);

  const Entity fresh = registry.create();
  ASSERT_EQ(fresh.index, old.index);
  registry.emplace(fresh, Position{3, 4});
  EXPECT_FALSE(registry.has<Position>(old));
  EXPECT_EQ(registry.tryGet<Position>(old), nullptr);
  EXPECT_TRUE(registry.has<Position>(fresh));
  EXPECT_EQ(registry.get<Position>(fresh), (Position{3, 4}));
}

TEST(Registry, EmplaceReplaceRemove) {
  Registry registry;
  const Entity a = registry.create();
  const Entity b = registry.create();
  EXPECT_FALSE(registry.has<Position>(a));
  EXPECT_EQ(registry.count<Position>(), 0u);

  EXPECT_EQ(registry.emplace(a, Position{1, 2}), (Position{1, 2}));
  registry.emplace<Label>(a, {"wall"});
  registry.emplace(b, Position{5, 6});
  EXPECT_EQ(registry.count<Position>(), 2u);
  EXPECT_EQ(registry.count<Label>(), 1u);
  EXPECT_EQ(registry.get<Label>(a).text, "wall");
  EXPECT_EQ(registry.tryGet<Label>(b), nullptr);

  registry.replace(a, Position{7, 8});
  EXPECT_EQ(registry.get<Position>(a), (Position{7, 8}));
  EXPECT_EQ(registry.get<Position>(b), (Position{5, 6}));

  EXPECT_EQ(registry.getOrEmplace<Label>(a, {"ignored"}).text, "wall");
  EXPECT_EQ(registry.getOrEmplace<Label>(b, {"floor"}).text, "floor");
  EXPECT_EQ(registry.emplaceOrReplace(b, Label{"roof"}).text, "roof");
  EXPECT_EQ(registry.count<Label>(), 2u);

  EXPECT_TRUE(registry.remove<Position>(a));
  EXPECT_FALSE(registry.remove<Position>(a));
  EXPECT_FALSE(registry.has<Position>(a));
  EXPECT_EQ(registry.get<Position>(b), (Position{5, 6}));  // swap-removal kept b's value
  EXPECT_EQ(registry.count<Position>(), 1u);
  EXPECT_FALSE(registry.remove<Selected>(a));  // a type with no pool yet

  registry.patch<Label>(a, [](Label& label) { label.text += " 2"; });
  EXPECT_EQ(registry.get<Label>(a).text, "wall 2");

  registry.destroy(a);
  EXPECT_EQ(registry.count<Label>(), 1u);
  EXPECT_EQ(registry.get<Label>(b).text, "roof");
}

TEST(Registry, EmptyComponentsAndMoveOnlyComponentsOutsideEdits) {
  Registry registry;
  const Entity a = registry.create();
  registry.emplace(a, Selected{});
  EXPECT_TRUE(registry.has<Selected>(a));

  // Move-only types are fine while nothing is recorded.
  registry.emplace(a, std::make_unique<int>(5));
  const Entity b = registry.create();
  registry.emplace(b, std::make_unique<int>(6));
  registry.replace(a, std::make_unique<int>(7));
  registry.patch<std::unique_ptr<int>>(b, [](std::unique_ptr<int>& value) { *value += 10; });
  EXPECT_EQ(*registry.get<std::unique_ptr<int>>(a), 7);
  EXPECT_EQ(*registry.get<std::unique_ptr<int>>(b), 16);
  registry.remove<std::unique_ptr<int>>(a);
  EXPECT_EQ(*registry.get<std::unique_ptr<int>>(b), 16);
  registry.destroy(b);
  EXPECT_EQ(registry.count<std::unique_ptr<int>>(), 0u);
}

TEST(Registry, VersionsCountMutationsPerType) {
  Registry registry;
  EXPECT_EQ(registry.version<Position>(), 0u);
  const Entity a = registry.create();
  EXPECT_EQ(registry.version<Position>(), 0u);  // creating an entity changes no component

  registry.emplace(a, Position{});
  const std::uint64_t after_emplace = registry.version<Position>();
  EXPECT_GT(after_emplace, 0u);

  (void)registry.get<Position>(a);
  (void)registry.has<Position>(a);
  for (auto [entity, position] : registry.view<Position>()) (void)position;
  EXPECT_EQ(registry.version<Position>(), after_emplace);  // reads change nothing

  registry.replace(a, Position{1, 0});
  const std::uint64_t after_replace = registry.version<Position>();
  EXPECT_GT(after_replace, after_emplace);

  registry.patch<Position>(a, [](Position& p) { p.y = 2; });
  const std::uint64_t after_patch = registry.version<Position>();
  EXPECT_GT(after_patch, after_replace);

  // Another type's changes leave Position's counter alone.
  registry.emplace(a, Label{"x"});
  registry.replace(a, Label{"y"});
  EXPECT_EQ(registry.version<Position>(), after_patch);
  EXPECT_GT(registry.version<Label>(), 0u);

  EXPECT_FALSE(registry.remove<Position>(registry.create()));
  EXPECT_EQ(registry.version<Position>(), after_patch);  // nothing removed

  registry.destroy(a);
  EXPECT_GT(registry.version<Position>(), after_patch);
}

// Entities of a view, as a set, so the unspecified order does not matter.
template <class... Ts>
std::set<Entity> viewed(const Registry& registry) {
  std::set<Entity> result;
  for (const auto& row : registry.view<Ts...>()) result.insert(std::get<0>(row));
  return result;
}

TEST(Registry, ViewsOverOneAndTwoComponentsWithRemovalsBetweenPasses) {
  //   entity:    0  1  2  3  4  5
  //   Position:  x  x  x  .  x  x
  //   Label:     x  .  x  x  .  x
  Registry registry;
  std::vector<Entity> e;
  for (int i = 0; i < 6; ++i) e.push_back(registry.create());
  for (std::size_t i : {0u, 1u, 2u, 4u, 5u}) registry.emplace(e[i], Position{double(i), 0});
  for (std::size_t i : {0u, 2u, 3u, 5u}) registry.emplace(e[i], Label{std::to_string(i)});

  EXPECT_EQ(viewed<Position>(registry), (std::set<Entity>{e[0], e[1], e[2], e[4], e[5]}));
  EXPECT_EQ(viewed<Label>(registry), (std::set<Entity>{e[0], e[2], e[3], e[5]}));
  EXPECT_EQ((viewed<Position, Label>(registry)), (std::set<Entity>{e[0], e[2], e[5]}));
  EXPECT_EQ((viewed<Label, Position>(registry)), (std::set<Entity>{e[0], e[2], e[5]}));
  EXPECT_TRUE(viewed<Selected>(registry).empty());  // a type never emplaced
  EXPECT_TRUE((viewed<Position, Selected>(registry).empty()));

  // Values arrive with their entities.
  int rows = 0;
  registry.view<Position, Label>().each([&](Entity entity, const Position& position, const Label& label) {
    EXPECT_EQ(position.x, double(entity.index));
    EXPECT_EQ(label.text, std::to_string(entity.index));
    ++rows;
  });
  EXPECT_EQ(rows, 3);

  registry.remove<Position>(e[0]);  // removes the first dense element: the last moves in
  EXPECT_EQ((viewed<Position, Label>(registry)), (std::set<Entity>{e[2], e[5]}));
  registry.destroy(e[5]);
  EXPECT_EQ((viewed<Position, Label>(registry)), (std::set<Entity>{e[2]}));
  EXPECT_EQ(viewed<Position>(registry), (std::set<Entity>{e[1], e[2], e[4]}));
  registry.emplace(e[4], Label{"4"});
  registry.emplace(e[0], Position{0, 0});
  EXPECT_EQ((viewed<Position, Label>(registry)), (std::set<Entity>{e[0], e[2], e[4]}));
  for (auto [entity, position, label] : registry.view<Position, Label>()) {
    EXPECT_EQ(position.x, double(entity.index));
    EXPECT_EQ(label.text, std::to_string(entity.index));
  }
}

TEST(Registry, ReplaceAndPatchInsideAViewAreAllowed) {
  Registry registry;
  for (int i = 0; i < 10; ++i) registry.emplace(registry.create(), Position{double(i), 0});
  registry.view<Position>().each(
      [&](Entity entity, const Position&) { registry.patch<Position>(entity, [](Position& p) { p.y = p.x * 2; }); });
  int visited = 0;
  for (auto [entity, position] : registry.view<Position>()) {
    EXPECT_EQ(position.y, position.x * 2);
    ++visited;
  }
  EXPECT_EQ(visited, 10);
}

#ifndef NDEBUG
TEST(RegistryDeathTest, MisuseAssertsWithAFix) {
  Registry registry;
  const Entity a = registry.create();
  registry.emplace(a, Position{});
  EXPECT_DEATH((void)registry.get<Label>(a), "check has<T>\\(\\) or use tryGet<T>\\(\\)");
  EXPECT_DEATH(registry.emplace(a, Position{}), "use replace or emplaceOrReplace");
  EXPECT_DEATH(registry.replace(a, Label{}), "use emplace or emplaceOrReplace");
  const Entity dead = registry.create();
  registry.destroy(dead);
  EXPECT_DEATH(registry.destroy(dead), "check alive\\(\\) first");
  EXPECT_DEATH(registry.emplace(dead, Label{}), "check alive\\(\\) first");
}

TEST(RegistryDeathTest, AddingOrRemovingViewedComponentsInsideTheLoopAsserts) {
  Registry registry;
  for (int i = 0; i < 4; ++i) registry.emplace(registry.create(), Position{});
  EXPECT_DEATH(
      registry.view<Position>().each([&](Entity entity, const Position&) { registry.remove<Position>(entity); }),
      "inside the loop: collect the entities");
  const auto grow_inside_loop = [&] {
    for (auto [entity, position] : registry.view<Position>()) registry.emplace(registry.create(), position);
  };
  EXPECT_DEATH(grow_inside_loop(), "collect the entities");
}
#endif

// Many entities, random operations with a fixed seed, checked against std::map models: swap-removal
// must keep every other entity's values where they belong.
TEST(Registry, RandomOperationsMatchAMapModel) {
  constexpr std::size_t kEntities = 100'000;
  constexpr int kOperations = 400'000;
  std::mt19937_64 random(20240611);  // the raw output is specified by the standard: same on any platform
  const auto below = [&](std::size_t bound) { return static_cast<std::size_t>(random() % bound); };

  Registry registry;
  std::vector<Entity> live;
  std::vector<Entity> dead;
  std::map<std::uint64_t, Position> positions;
  std::map<std::uint64_t, Label> labels;
  for (std::size_t i = 0; i < kEntities; ++i) live.push_back(registry.create());

  for (int step = 0; step < kOperations; ++step) {
    const std::size_t which = below(live.size());
    const Entity entity = live[which];
    const double value = static_cast<double>(step);
    switch (below(8)) {
      case 0: {  // destroy, then create so the population stays near kEntities
        registry.destroy(entity);
        positions.erase(entity.id());
        labels.erase(entity.id());
        dead.push_back(entity);
        live[which] = live.back();
        live.pop_back();
        live.push_back(registry.create());
        break;
      }
      case 1:
      case 2:
        registry.emplaceOrReplace(entity, Position{value, -value});
        positions[entity.id()] = Position{value, -value};
        break;
      case 3:
        EXPECT_EQ(registry.remove<Position>(entity), positions.erase(entity.id()) == 1);
        break;
      case 4:
      case 5:
        registry.emplaceOrReplace(entity, Label{"label " + std::to_string(step)});
        labels[entity.id()] = Label{"label " + std::to_string(step)};
        break;
      case 6:
        EXPECT_EQ(registry.remove<Label>(entity), labels.erase(entity.id()) == 1);
        break;
      case 7:
        if (registry.has<Position>(entity)) {
          registry.patch<Position>(entity, [](Position& p) { p.y += 1; });
          positions[entity.id()].y += 1;
        }
        break;
    }
  }

  ASSERT_EQ(registry.size(), live.size());
  ASSERT_EQ(registry.count<Position>(), positions.size());
  ASSERT_EQ(registry.count<Label>(), labels.size());
  std::size_t mismatches = 0;
  std::size_t both = 0;
  for (const Entity entity : live) {
    ASSERT_TRUE(registry.alive(entity));
    const auto position = positions.find(entity.id());
    const auto label = labels.find(entity.id());
    const Position* stored_position = registry.tryGet<Position>(entity);
    const Label* stored_label = registry.tryGet<Label>(entity);
    if ((position == positions.end()) != (stored_position == nullptr)) ++mismatches;
    if (stored_position != nullptr && position != positions.end() && !(*stored_position == position->second)) {
      ++mismatches;
    }
    if ((label == labels.end()) != (stored_label == nullptr)) ++mismatches;
    if (stored_label != nullptr && label != labels.end() && !(*stored_label == label->second)) ++mismatches;
    if (position != positions.end() && label != labels.end()) ++both;
  }
  EXPECT_EQ(mismatches, 0u);
  for (const Entity entity : dead) {
    EXPECT_FALSE(registry.alive(entity));
    EXPECT_FALSE(registry.has<Position>(entity));
  }
  EXPECT_GT(dead.size(), 10'000u);  // the walk did exercise recycling

  std::size_t viewed_rows = 0;
  registry.view<Label, Position>().each([&](Entity entity, const Label& label, const Position& position) {
    ++viewed_rows;
    EXPECT_EQ(labels.at(entity.id()), label);
    EXPECT_EQ(positions.at(entity.id()), position);
  });
  EXPECT_EQ(viewed_rows, both);
  EXPECT_GT(both, 1000u);
}

}  // namespace
}  // namespace plumb::ecs
