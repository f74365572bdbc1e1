#include "engine/ecs/history.h"

#include <cassert>
#include <exception>
#include <functional>
#include <utility>

#include "engine/ecs/registry.h"

namespace plumb::ecs {

std::size_t History::ChangeKeyHash::operator()(const ChangeKey& key) const noexcept {
  // The ids are small and dense; a multiply spreads them before the combine.
  return std::hash<std::uint64_t>{}(key.entity_id * 0x9e3779b97f4a7c15ULL ^ key.type);
}

History::History(Registry& registry, std::size_t max_edits) : registry_(registry), max_edits_(max_edits) {
  assert(registry_.history_ == nullptr && "the registry has a History already: a registry has at most one");
  registry_.history_ = this;
}

History::~History() {
  if (open_) {
    Edit edit = std::move(current_);
    close();
    releaseApplied(edit);
  }
  clear();
  registry_.history_ = nullptr;
}

void History::begin(std::string name) {
  assert(!open_ && "an edit is already open: commit or cancel it first (edits do not nest)");
  if (open_) return;
  open_ = true;
  current_ = Edit{std::move(name), {}};
  registry_.recording_ = true;
}

void History::commit() {
  assert(open_ && "commit without an open edit: call begin first");
  if (!open_) return;
  Edit edit = std::move(current_);
  close();
  // A component added and removed again within the edit left no trace.
  std::erase_if(edit.changes, [](const Change& change) {
    return change.kind == Change::Kind::kComponent && change.before == nullptr && change.after == nullptr;
  });
  if (edit.changes.empty()) return;
  for (const Edit& undone : redo_) releaseUndone(undone);
  redo_.clear();
  undo_.push_back(std::move(edit));
  trim();
}

void History::cancel() {
  assert(open_ && "cancel without an open edit: call begin first");
  if (!open_) return;
  Edit edit = std::move(current_);
  close();
  revert(edit);
  releaseUndone(edit);
}

bool History::undo() {
  assert(!open_ && "undo while an edit is open: commit or cancel it first");
  if (open_ || undo_.empty()) return false;
  Edit edit = std::move(undo_.back());
  undo_.pop_back();
  revert(edit);
  redo_.push_back(std::move(edit));
  return true;
}

bool History::redo() {
  assert(!open_ && "redo while an edit is open: commit or cancel it first");
  if (open_ || redo_.empty()) return false;
  Edit edit = std::move(redo_.back());
  redo_.pop_back();
  reapply(edit);
  undo_.push_back(std::move(edit));
  return true;
}

void History::clear() {
  for (const Edit& edit : undo_) releaseApplied(edit);
  for (const Edit& edit : redo_) releaseUndone(edit);
  undo_.clear();
  redo_.clear();
}

void History::setMaxEdits(std::size_t max_edits) {
  max_edits_ = max_edits;
  trim();
}

void History::record(Change&& change) {
  assert(open_ && "the registry records only while an edit is open");
  if (change.kind != Change::Kind::kComponent) {
    current_.changes.push_back(std::move(change));
    return;
  }
  // Reverting the merged change restores the first before, reapplying it sets the last after;
  // nothing else in the edit depends on the values in between.
  const ChangeKey key{change.entity.id(), change.component_type};
  const auto [it, inserted] = current_index_.try_emplace(key, current_.changes.size());
  if (inserted) {
    current_.changes.push_back(std::move(change));
  } else {
    current_.changes[it->second].after = std::move(change.after);
  }
}

void History::close() {
  open_ = false;
  registry_.recording_ = false;
  current_ = Edit{};
  current_index_.clear();
}

void History::revert(const Edit& edit) {
  for (auto it = edit.changes.rbegin(); it != edit.changes.rend(); ++it) {
    const Change& change = *it;
    bool applied = true;
    switch (change.kind) {
      case Change::Kind::kComponent:
        applied = change.set_component(registry_, change.entity, change.before.get());
        break;
      case Change::Kind::kCreate:
        // Held, not freed: redo brings the same handle back.
        applied = registry_.alive(change.entity);
        if (applied) registry_.destroyEntity(change.entity, /*hold=*/true);
        break;
      case Change::Kind::kDestroy:
        applied = registry_.revive(change.entity);
        break;
    }
    if (!applied) ++skipped_changes_;
  }
}

void History::reapply(const Edit& edit) {
  for (const Change& change : edit.changes) {
    bool applied = true;
    switch (change.kind) {
      case Change::Kind::kComponent:
        applied = change.set_component(registry_, change.entity, change.after.get());
        break;
      case Change::Kind::kCreate:
        applied = registry_.revive(change.entity);
        break;
      case Change::Kind::kDestroy:
        applied = registry_.alive(change.entity);
        if (applied) registry_.destroyEntity(change.entity, /*hold=*/true);
        break;
    }
    if (!applied) ++skipped_changes_;
  }
}

// Within one edit an entity is created at most once, before anything else happens to it, and
// destroyed at most once, after everything else (only undo revives). So an applied edit keeps
// exactly the entities it destroyed out of reuse, and an undone edit exactly those it created.
void History::releaseApplied(const Edit& edit) {
  for (const Change& change : edit.changes) {
    if (change.kind == Change::Kind::kDestroy) registry_.release(change.entity);
  }
}

void History::releaseUndone(const Edit& edit) {
  for (const Change& change : edit.changes) {
    if (change.kind == Change::Kind::kCreate) registry_.release(change.entity);
  }
}

void History::trim() {
  while (undo_.size() > max_edits_) {
    releaseApplied(undo_.front());
    undo_.pop_front();
  }
}

EditScope::EditScope(History& history, std::string name)
    : history_(history.isOpen() ? nullptr : &history), uncaught_exceptions_(std::uncaught_exceptions()) {
  history.begin(std::move(name));  // asserts when nested
}

EditScope::~EditScope() {
  if (history_ == nullptr) return;
  if (std::uncaught_exceptions() > uncaught_exceptions_) {
    history_->cancel();
  } else {
    history_->commit();
  }
}

void EditScope::commit() {
  if (history_ != nullptr) history_->commit();
  history_ = nullptr;
}

void EditScope::cancel() {
  if (history_ != nullptr) history_->cancel();
  history_ = nullptr;
}

}  // namespace plumb::ecs
