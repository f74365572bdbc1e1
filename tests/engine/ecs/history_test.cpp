#include "engine/ecs/history.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/ecs/registry.h"

namespace plumb::ecs {
namespace {

struct Position {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Position&) const = default;
};

struct Label {
  std::string text;
  bool operator==(const Label&) const = default;
};

TEST(History, UndoAndRedoEmplace) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();  // outside an edit: not recorded

  history.begin("Add position");
  EXPECT_TRUE(registry.recording());
  registry.emplace(a, Position{1, 2});
  history.commit();
  EXPECT_FALSE(registry.recording());
  EXPECT_TRUE(history.canUndo());
  EXPECT_FALSE(history.canRedo());
  EXPECT_EQ(history.undoName(), "Add position");

  const std::uint64_t version = registry.version<Position>();
  EXPECT_TRUE(history.undo());
  EXPECT_FALSE(registry.has<Position>(a));
  EXPECT_TRUE(registry.alive(a));
  EXPECT_GT(registry.version<Position>(), version);  // a renderer sees undo too
  EXPECT_FALSE(history.canUndo());
  EXPECT_EQ(history.redoName(), "Add position");
  EXPECT_FALSE(history.undo());

  EXPECT_TRUE(history.redo());
  EXPECT_EQ(registry.get<Position>(a), (Position{1, 2}));
  EXPECT_FALSE(history.redo());
  EXPECT_EQ(history.undoName(), "Add position");
  EXPECT_EQ(history.redoName(), "");
}

TEST(History, UndoAndRedoReplaceAndRemove) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  registry.emplace(a, Position{1, 1});
  registry.emplace(a, Label{"before"});

  history.begin("Edit");
  registry.replace(a, Position{2, 2});
  registry.remove<Label>(a);
  history.commit();
  EXPECT_EQ(registry.get<Position>(a), (Position{2, 2}));
  EXPECT_FALSE(registry.has<Label>(a));

  history.undo();
  EXPECT_EQ(registry.get<Position>(a), (Position{1, 1}));
  EXPECT_EQ(registry.get<Label>(a).text, "before");

  history.redo();
  EXPECT_EQ(registry.get<Position>(a), (Position{2, 2}));
  EXPECT_FALSE(registry.has<Label>(a));
}

TEST(History, UndoCreationDestroysAndRedoBringsTheSameHandleBack) {
  Registry registry;
  History history(registry);
  history.begin("Add polygon");
  const Entity polygon = registry.create();
  registry.emplace(polygon, Label{"roof"});
  history.commit();

  history.undo();
  EXPECT_FALSE(registry.alive(polygon));
  EXPECT_EQ(registry.size(), 0u);
  EXPECT_EQ(registry.count<Label>(), 0u);

  // A transient entity made between undo and redo must not take the held index.
  const Entity transient = registry.create();
  EXPECT_NE(transient.index, polygon.index);

  history.redo();
  EXPECT_TRUE(registry.alive(polygon));
  EXPECT_EQ(registry.get<Label>(polygon).text, "roof");
  EXPECT_EQ(registry.size(), 2u);
}

TEST(History, UndoDestroyRestoresTheSameHandleAndItsComponents) {
  Registry registry;
  History history(registry);
  const Entity keep = registry.create();
  const Entity victim = registry.create();
  registry.emplace(victim, Position{3, 4});
  registry.emplace(victim, Label{"wall"});
  registry.emplace(keep, Position{9, 9});

  history.begin("Delete polygon");
  registry.destroy(victim);
  history.commit();
  EXPECT_FALSE(registry.alive(victim));
  EXPECT_EQ(registry.count<Position>(), 1u);

  // Tool state created outside edits (hover markers) must not reuse the index.
  const Entity marker = registry.create();
  EXPECT_NE(marker.index, victim.index);
  registry.destroy(marker);

  history.undo();
  ASSERT_TRUE(registry.alive(victim));
  EXPECT_EQ(registry.get<Position>(victim), (Position{3, 4}));
  EXPECT_EQ(registry.get<Label>(victim).text, "wall");
  EXPECT_EQ(registry.get<Position>(keep), (Position{9, 9}));
  EXPECT_EQ(registry.size(), 2u);

  history.redo();
  EXPECT_FALSE(registry.alive(victim));
  EXPECT_EQ(registry.count<Label>(), 0u);
  history.undo();
  EXPECT_TRUE(registry.alive(victim));
  EXPECT_EQ(history.skippedChanges(), 0u);
}

TEST(History, SeveralEditsUndoAndRedoInOrder) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  registry.emplace(a, Position{0, 0});
  for (int i = 1; i <= 3; ++i) {
    EditScope scope(history, "Move " + std::to_string(i));
    registry.replace(a, Position{double(i), 0});
  }
  EXPECT_EQ(history.undoCount(), 3u);
  EXPECT_EQ(history.undoName(), "Move 3");
  history.undo();
  history.undo();
  EXPECT_EQ(registry.get<Position>(a).x, 1.0);
  EXPECT_EQ(history.undoName(), "Move 1");
  EXPECT_EQ(history.redoName(), "Move 2");
  history.redo();
  EXPECT_EQ(registry.get<Position>(a).x, 2.0);
  history.redo();
  EXPECT_EQ(registry.get<Position>(a).x, 3.0);
  EXPECT_FALSE(history.canRedo());
}

TEST(History, ANewEditAfterUndoDropsTheRedoList) {
  Registry registry;
  History history(registry);
  history.begin("Create");
  const Entity created = registry.create();
  registry.emplace(created, Position{1, 1});
  history.commit();
  history.undo();
  EXPECT_TRUE(history.canRedo());

  const Entity other = registry.create();
  history.begin("Label");
  registry.emplace(other, Label{"new"});
  history.commit();
  EXPECT_FALSE(history.canRedo());
  EXPECT_EQ(history.redoName(), "");
  EXPECT_FALSE(history.redo());

  // The undone creation's index is free again, with the next generation.
  const Entity reused = registry.create();
  EXPECT_EQ(reused.index, created.index);
  EXPECT_EQ(reused.generation, created.generation + 1);
  EXPECT_FALSE(registry.alive(created));
}

TEST(History, CancelRevertsTheOpenEditAndKeepsRedo) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  const Entity b = registry.create();
  registry.emplace(a, Position{1, 1});
  registry.emplace(b, Label{"b"});
  history.begin("Kept");
  registry.replace(a, Position{2, 2});
  history.commit();
  history.undo();

  history.begin("Abandoned");
  registry.replace(a, Position{5, 5});
  const Entity c = registry.create();
  registry.emplace(c, Label{"c"});
  registry.destroy(b);
  registry.emplace(a, Label{"a"});
  EXPECT_EQ(history.openChangeCount(), 6u);  // replace, create, emplace, remove label, destroy, emplace
  history.cancel();

  EXPECT_FALSE(history.isOpen());
  EXPECT_FALSE(registry.recording());
  EXPECT_EQ(registry.get<Position>(a), (Position{1, 1}));
  EXPECT_FALSE(registry.has<Label>(a));
  EXPECT_TRUE(registry.alive(b));
  EXPECT_EQ(registry.get<Label>(b).text, "b");
  EXPECT_FALSE(registry.alive(c));
  EXPECT_EQ(registry.size(), 2u);
  EXPECT_EQ(registry.count<Label>(), 1u);
  EXPECT_EQ(history.redoName(), "Kept");
  EXPECT_FALSE(history.canUndo());

  history.redo();
  EXPECT_EQ(registry.get<Position>(a), (Position{2, 2}));

  // The cancelled creation's index is not held forever.
  const Entity next = registry.create();
  EXPECT_EQ(next.index, c.index);
}

TEST(History, EmptyEditsAreDropped) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  history.begin("Nothing");
  history.commit();
  EXPECT_FALSE(history.canUndo());

  history.begin("Round trip");
  registry.emplace(a, Position{});
  registry.remove<Position>(a);
  history.commit();
  EXPECT_FALSE(history.canUndo());

  // An empty edit after undo keeps the redo list.
  history.begin("Move");
  registry.emplace(a, Position{1, 0});
  history.commit();
  history.undo();
  history.begin("Nothing");
  history.commit();
  EXPECT_TRUE(history.canRedo());
}

TEST(History, ChangesOutsideAnEditAreNotRecorded) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  registry.emplace(a, Position{1, 1});
  registry.replace(a, Position{2, 2});
  registry.destroy(registry.create());
  EXPECT_FALSE(history.canUndo());

  history.begin("Move");
  registry.replace(a, Position{3, 3});
  history.commit();
  registry.replace(a, Position{4, 4});  // a grower snapshot, say
  history.undo();
  EXPECT_EQ(registry.get<Position>(a), (Position{2, 2}));
  EXPECT_FALSE(history.canUndo());
}

TEST(History, RepeatedChangesInOneEditAreMerged) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  registry.emplace(a, Position{0, 0});
  {
    EditScope drag(history, "Drag");
    for (int frame = 0; frame < 100; ++frame) registry.patch<Position>(a, [](Position& p) { p.x += 1; });
    EXPECT_EQ(history.openChangeCount(), 1u);
  }
  EXPECT_EQ(registry.get<Position>(a).x, 100.0);
  history.undo();
  EXPECT_EQ(registry.get<Position>(a).x, 0.0);
  history.redo();
  EXPECT_EQ(registry.get<Position>(a).x, 100.0);
}

TEST(History, ACreatedAndDestroyedEntityInOneEditRoundTrips) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  history.begin("Scratch");
  const Entity scratch = registry.create();
  registry.emplace(scratch, Label{"tmp"});
  registry.emplace(a, Label{"a"});
  registry.destroy(scratch);
  history.commit();
  history.undo();
  EXPECT_FALSE(registry.alive(scratch));
  EXPECT_FALSE(registry.has<Label>(a));
  EXPECT_EQ(registry.count<Label>(), 0u);
  history.redo();
  EXPECT_FALSE(registry.alive(scratch));
  EXPECT_EQ(registry.get<Label>(a).text, "a");
  EXPECT_EQ(registry.size(), 1u);
}

TEST(History, EditScopeCommitsOrCancelsOnException) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  {
    EditScope scope(history, "Label");
    registry.emplace(a, Label{"x"});
  }
  EXPECT_EQ(history.undoName(), "Label");

  EXPECT_THROW(
      {
        EditScope scope(history, "Fails");
        registry.replace(a, Label{"y"});
        throw std::runtime_error("tool failed");
      },
      std::runtime_error);
  EXPECT_FALSE(history.isOpen());
  EXPECT_EQ(registry.get<Label>(a).text, "x");
  EXPECT_EQ(history.undoCount(), 1u);

  {
    EditScope scope(history, "Changed my mind");
    registry.replace(a, Label{"z"});
    scope.cancel();
    EXPECT_FALSE(history.isOpen());
  }
  EXPECT_EQ(registry.get<Label>(a).text, "x");
  EXPECT_EQ(history.undoCount(), 1u);
}

TEST(History, TheCapForgetsTheOldestEdits) {
  Registry registry;
  History history(registry, 3);
  EXPECT_EQ(history.maxEdits(), 3u);
  const Entity a = registry.create();
  registry.emplace(a, Position{0, 0});
  std::vector<Entity> deleted;
  for (int i = 1; i <= 5; ++i) {
    const Entity doomed = registry.create();
    EditScope scope(history, "Step " + std::to_string(i));
    registry.replace(a, Position{double(i), 0});
    registry.destroy(doomed);
    deleted.push_back(doomed);
  }
  EXPECT_EQ(history.undoCount(), 3u);
  while (history.undo()) {
  }
  EXPECT_EQ(registry.get<Position>(a).x, 2.0);  // steps 1 and 2 were forgotten
  EXPECT_FALSE(registry.alive(deleted[0]));
  EXPECT_FALSE(registry.alive(deleted[1]));
  EXPECT_TRUE(registry.alive(deleted[2]));
  EXPECT_TRUE(registry.alive(deleted[4]));

  // The indices the forgotten edits held are free again.
  const Entity reused = registry.create();
  EXPECT_TRUE(reused.index == deleted[0].index || reused.index == deleted[1].index);

  while (history.redo()) {
  }
  EXPECT_EQ(registry.get<Position>(a).x, 5.0);
  history.setMaxEdits(1);
  EXPECT_EQ(history.undoCount(), 1u);
  EXPECT_TRUE(history.undo());
  EXPECT_FALSE(history.undo());
  EXPECT_EQ(registry.get<Position>(a).x, 4.0);
}

TEST(History, TheDefaultCapIsAThousandEdits) {
  Registry registry;
  History history(registry);
  EXPECT_EQ(history.maxEdits(), 1000u);
  const Entity a = registry.create();
  registry.emplace(a, Position{0, 0});
  for (int i = 1; i <= 1005; ++i) {
    EditScope scope(history, "Step");
    registry.replace(a, Position{double(i), 0});
  }
  EXPECT_EQ(history.undoCount(), 1000u);
  while (history.undo()) {
  }
  EXPECT_EQ(registry.get<Position>(a).x, 5.0);
}

TEST(History, ChangesOutsideEditsThatBreakTheLogAreCountedNotApplied) {
  Registry registry;
  History history(registry);
  history.begin("Create");
  const Entity a = registry.create();
  registry.emplace(a, Label{"a"});
  history.commit();
  registry.destroy(a);  // outside an edit: the log cannot know
  const Entity b = registry.create();
  ASSERT_EQ(b.index, a.index);  // the index went back to the free list and was reused

  history.undo();  // neither the label removal nor the destruction can apply
  EXPECT_EQ(history.skippedChanges(), 2u);
  EXPECT_TRUE(registry.alive(b));
  history.redo();  // b holds the index: a cannot come back
  EXPECT_FALSE(registry.alive(a));
  EXPECT_EQ(history.skippedChanges(), 4u);
  EXPECT_EQ(registry.count<Label>(), 0u);
}

TEST(History, DestroyingTheHistoryFreesTheIndicesItHeld) {
  Registry registry;
  const Entity victim = registry.create();
  {
    History history(registry);
    history.begin("Delete");
    registry.destroy(victim);
    history.commit();
    EXPECT_NE(registry.create().index, victim.index);
  }
  EXPECT_EQ(registry.create().index, victim.index);
  History again(registry);  // the registry can take a new history
  EXPECT_FALSE(again.canUndo());
}

#ifndef NDEBUG
TEST(HistoryDeathTest, MisuseAsserts) {
  Registry registry;
  History history(registry);
  history.begin("Outer");
  EXPECT_DEATH(history.begin("Inner"), "edits do not nest");
  EXPECT_DEATH({ EditScope inner(history, "Inner"); }, "edits do not nest");
  EXPECT_DEATH(history.undo(), "commit or cancel it first");
  EXPECT_DEATH(history.redo(), "commit or cancel it first");
  history.commit();
  EXPECT_DEATH(history.commit(), "call begin first");
  EXPECT_DEATH(history.cancel(), "call begin first");
  EXPECT_DEATH(History second(registry), "at most one");
}

TEST(HistoryDeathTest, MoveOnlyComponentsCannotBeRecorded) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  history.begin("Edit");
  EXPECT_DEATH(registry.emplace(a, std::make_unique<int>(1)), "make it copyable");
  history.cancel();
}
#else
TEST(History, NestedBeginIsIgnoredInReleaseBuilds) {
  Registry registry;
  History history(registry);
  const Entity a = registry.create();
  history.begin("Outer");
  {
    EditScope inner(history, "Inner");  // joins the outer edit instead of committing it
    registry.emplace(a, Position{1, 1});
  }
  EXPECT_TRUE(history.isOpen());
  EXPECT_FALSE(history.undo());
  history.commit();
  EXPECT_EQ(history.undoName(), "Outer");
}
#endif

// Random edits, undos and redos with a fixed seed: after every step the registry must equal the
// snapshot taken when the history was last at that position.
using Snapshot = std::map<std::uint64_t, std::pair<std::optional<Position>, std::optional<Label>>>;

Snapshot snapshot(const Registry& registry, const std::vector<Entity>& ever_created) {
  Snapshot result;
  for (const Entity entity : ever_created) {
    if (!registry.alive(entity)) continue;
    auto& [position, label] = result[entity.id()];
    if (const Position* p = registry.tryGet<Position>(entity)) position = *p;
    if (const Label* l = registry.tryGet<Label>(entity)) label = *l;
  }
  return result;
}

TEST(History, RandomEditsUndoAndRedoMatchSnapshots) {
  std::mt19937_64 random(77);
  const auto below = [&](std::size_t bound) { return static_cast<std::size_t>(random() % bound); };
  Registry registry;
  History history(registry, 50);
  std::vector<Entity> ever_created;
  for (int i = 0; i < 20; ++i) ever_created.push_back(registry.create());

  // states[k] is the registry after k edits of the current undo list; states.size() - 1 == undo
  // position + redo count.
  std::vector<Snapshot> states{snapshot(registry, ever_created)};
  std::size_t position = 0;
  for (int step = 0; step < 3000; ++step) {
    const std::size_t action = below(10);
    if (action < 2) {
      ASSERT_EQ(history.undo(), position > 0);
      if (position > 0) --position;
    } else if (action < 4) {
      ASSERT_EQ(history.redo(), position + 1 < states.size());
      if (position + 1 < states.size()) ++position;
    } else {
      history.begin("Step " + std::to_string(step));
      const std::size_t changes = 1 + below(4);
      for (std::size_t c = 0; c < changes; ++c) {
        std::vector<Entity> live;
        for (const Entity entity : ever_created) {
          if (registry.alive(entity)) live.push_back(entity);
        }
        const Entity target = live.empty() ? kNullEntity : live[below(live.size())];
        switch (live.empty() ? 0 : below(6)) {
          case 0:
            ever_created.push_back(registry.create());
            break;
          case 1:
            registry.destroy(target);
            break;
          case 2:
            registry.emplaceOrReplace(target, Position{double(step), double(c)});
            break;
          case 3:
            registry.remove<Position>(target);
            break;
          case 4:
            registry.emplaceOrReplace(target, Label{std::to_string(step)});
            break;
          case 5:
            registry.remove<Label>(target);
            break;
        }
      }
      if (below(8) == 0) {
        history.cancel();
      } else {
        history.commit();
        if (history.undoName() == "Step " + std::to_string(step)) {  // not dropped as empty
          states.resize(position + 1);
          states.push_back(snapshot(registry, ever_created));
          ++position;
          if (states.size() > 51) {  // the cap forgot the oldest
            states.erase(states.begin());
            --position;
          }
        }
      }
    }
    ASSERT_EQ(history.undoCount(), position) << "step " << step;
    ASSERT_EQ(history.redoCount(), states.size() - 1 - position) << "step " << step;
    ASSERT_EQ(snapshot(registry, ever_created), states[position]) << "step " << step;
  }
  EXPECT_EQ(history.skippedChanges(), 0u);
}

}  // namespace
}  // namespace plumb::ecs
