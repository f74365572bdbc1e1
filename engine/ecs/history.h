#pragma once
// Undo and redo for a Registry, as a log of edits. An edit is a named group of changes:
//
//   history.begin("Move polygon");
//   registry.patch<Outline>(polygon, [&](Outline& o) { o.translate(delta); });
//   history.commit();              // or: EditScope scope(history, "Move polygon");
//   ...
//   history.undo();                // the outline is back where it was
//
// While an edit is open every mutation made through the registry is recorded: entity creation,
// destruction (preceded by the removal of each of its components) and each component's value
// before and after (absent counts as a value). Mutations outside an open edit are not recorded, so
// the app can apply grower snapshots and transient tool state every frame without filling the
// history; keep those off the entities and component types that edits change, or undo will
// restore values from before them. Repeated changes of one component of one entity inside one
// edit are kept as one (a drag records a single before and after).
//
// Destroying an entity during an edit keeps its index out of reuse while the edit is in the log,
// so undo brings back the same handle with its components; likewise an undone creation keeps its
// handle for redo. Components changed in edits must be copyable (registry.h).
//
// Not thread-safe; use it on the registry's thread.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/ecs/change.h"
#include "engine/ecs/entity.h"

namespace plumb::ecs {

class Registry;

class History {
 public:
  static constexpr std::size_t kDefaultMaxEdits = 1000;

  // Attaches to `registry`, which must have no other History (asserted) and must outlive this one.
  // Keeps at most `max_edits` edits to undo; older ones are forgotten.
  explicit History(Registry& registry, std::size_t max_edits = kDefaultMaxEdits);
  // Detaches from the registry. An open edit is closed as it stands (not reverted) and forgotten.
  ~History();
  History(const History&) = delete;
  History& operator=(const History&) = delete;

  // --- Recording --------------------------------------------------------------------------------

  // Opens an edit named `name` (what undoName() shows, e.g. "Move polygon"). Edits do not nest:
  // one must not be open (asserted; in release builds the call is ignored and the open edit
  // continues). EditScope is the exception-safe way to call this.
  void begin(std::string name);

  // Closes the open edit (asserted) and puts it on the undo list. An edit that changed nothing is
  // dropped and leaves the redo list alone; any other clears the redo list and may push the oldest
  // edit out of the log (maxEdits).
  void commit();

  // Reverts the open edit's changes (asserted open), newest first, and forgets it. The redo list
  // is kept: the registry is back where it was when the edit began.
  void cancel();

  // True between begin and commit or cancel.
  bool isOpen() const { return open_; }
  // The number of changes the open edit holds so far (0 when none is open).
  std::size_t openChangeCount() const { return open_ ? current_.changes.size() : 0; }

  // --- Undo and redo ----------------------------------------------------------------------------
  // Both assert that no edit is open and return false when there is nothing to do. Their own
  // mutations are not recorded; they bump the versions of the component types they touch.

  // Reverts the newest edit, its changes newest first, and moves it to the redo list.
  bool undo();
  // Reapplies the edit undo reverted last, oldest change first, and moves it back.
  bool redo();

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  // The name of the edit undo() or redo() would revert or reapply; empty when there is none.
  std::string_view undoName() const { return undo_.empty() ? std::string_view{} : undo_.back().name; }
  std::string_view redoName() const { return redo_.empty() ? std::string_view{} : redo_.back().name; }
  std::size_t undoCount() const { return undo_.size(); }
  std::size_t redoCount() const { return redo_.size(); }

  // Changes undo or redo could not apply because their entity was destroyed, or its index reused,
  // outside an edit. Counted since construction; nonzero means the app broke the rule above.
  std::size_t skippedChanges() const { return skipped_changes_; }

  // Forgets every edit to undo and redo (an open edit stays open).
  void clear();

  std::size_t maxEdits() const { return max_edits_; }
  // Forgets the oldest edits beyond `max_edits` now and from then on; 0 keeps none.
  void setMaxEdits(std::size_t max_edits);

 private:
  friend class Registry;

  struct Edit {
    std::string name;
    std::vector<Change> changes;  // in the order they happened
  };
  // One component of one entity, to merge repeated changes within the open edit.
  struct ChangeKey {
    std::uint64_t entity_id;
    ComponentTypeId type;
    bool operator==(const ChangeKey&) const = default;
  };
  struct ChangeKeyHash {
    std::size_t operator()(const ChangeKey& key) const noexcept;
  };

  // Called by the registry for each mutation while an edit is open.
  void record(Change&& change);

  void close();
  void revert(const Edit& edit);
  void reapply(const Edit& edit);
  // Let the registry reuse the indices an edit keeps from reuse: those it destroyed when it
  // leaves the log applied, those it created when it leaves the log undone.
  void releaseApplied(const Edit& edit);
  void releaseUndone(const Edit& edit);
  void trim();

  Registry& registry_;
  std::size_t max_edits_;
  std::deque<Edit> undo_;   // oldest first
  std::vector<Edit> redo_;  // the next to redo last
  bool open_ = false;
  Edit current_;                                                             // the open edit
  std::unordered_map<ChangeKey, std::size_t, ChangeKeyHash> current_index_;  // into current_.changes
  std::size_t skipped_changes_ = 0;
};

// Opens an edit for the lifetime of a scope: commits it on leaving normally, cancels it when the
// scope is left by an exception. Not nestable (History::begin); commit() or cancel() end it early.
class EditScope {
 public:
  EditScope(History& history, std::string name);
  ~EditScope();
  EditScope(const EditScope&) = delete;
  EditScope& operator=(const EditScope&) = delete;

  void commit();
  void cancel();

 private:
  History* history_;  // null once ended, or when the scope did not open the edit
  int uncaught_exceptions_;
};

}  // namespace plumb::ecs
