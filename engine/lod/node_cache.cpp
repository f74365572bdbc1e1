#include "engine/lod/node_cache.h"

#include <tbb/task_group.h>

#include <condition_variable>
#include <exception>

namespace plumb::lod {

struct NodeCache::Background {
  tbb::task_group loads;  // without a runner
  BackgroundRunner runner;
  std::mutex mutex;  // guards outstanding
  std::condition_variable done;
  std::size_t outstanding = 0;  // loads handed to the runner and not finished
};

struct NodeCache::Entry {
  std::shared_ptr<const NodePoints> points;  // set once loaded
  std::exception_ptr error;                  // set if the load failed
  bool loading = true;
  std::size_t bytes = 0;
  std::list<CellKey>::iterator recency;
};

NodeCache::NodeCache(std::shared_ptr<const Octree> octree, std::size_t budget_bytes)
    : octree_(std::move(octree)), budget_bytes_(budget_bytes), background_(std::make_unique<Background>()) {}

NodeCache::~NodeCache() {
  background_->loads.wait();
  std::unique_lock lock(background_->mutex);
  background_->done.wait(lock, [&] { return background_->outstanding == 0; });
}

void NodeCache::setBackgroundRunner(BackgroundRunner runner) {
  background_->runner = std::move(runner);
}

void NodeCache::loadInBackground(const std::shared_ptr<Entry>& entry, const NodeInfo& node) {
  Background& background = *background_;
  if (!background.runner) {
    background.loads.run([this, entry, node] { load(entry, node); });
    return;
  }
  {
    const std::scoped_lock lock(background.mutex);
    ++background.outstanding;
  }
  background.runner([this, entry, node] {
    load(entry, node);
    const std::scoped_lock lock(background_->mutex);
    if (--background_->outstanding == 0) background_->done.notify_all();
  });
}

std::shared_ptr<NodeCache::Entry> NodeCache::acquire(const NodeInfo& node, bool& must_load) {
  // Called with mutex_ held.
  const auto it = entries_.find(node.key);
  if (it != entries_.end()) {
    recency_.splice(recency_.begin(), recency_, it->second->recency);
    ++stats_.hits;
    must_load = false;
    return it->second;
  }
  auto entry = std::make_shared<Entry>();
  recency_.push_front(node.key);
  entry->recency = recency_.begin();
  entries_.emplace(node.key, entry);
  ++stats_.misses;
  stats_.bytes_read += node.bytes;
  must_load = true;
  return entry;
}

void NodeCache::load(const std::shared_ptr<Entry>& entry, const NodeInfo& node) {
  std::shared_ptr<const NodePoints> points;
  std::exception_ptr error;
  try {
    points = std::make_shared<const NodePoints>(octree_->load(node));
  } catch (...) {
    error = std::current_exception();
  }
  {
    const std::lock_guard lock(mutex_);
    entry->loading = false;
    if (error) {
      // Forget the entry so that a later request tries again (the file may be repaired).
      entry->error = error;
      recency_.erase(entry->recency);
      entries_.erase(node.key);
    } else {
      entry->points = points;
      entry->bytes = points->bytes();
      stats_.bytes += entry->bytes;
      evictOverBudget();
    }
  }
  loaded_.notify_all();
}

std::shared_ptr<const NodePoints> NodeCache::wait(const std::shared_ptr<Entry>& entry) {
  std::unique_lock lock(mutex_);
  loaded_.wait(lock, [&] { return !entry->loading; });
  if (entry->error) std::rethrow_exception(entry->error);
  return entry->points;
}

void NodeCache::evictOverBudget() {
  // Called with mutex_ held. The least recently used loaded entries go first; the most recent
  // one stays even if it alone exceeds the budget.
  auto it = recency_.end();
  while (stats_.bytes > budget_bytes_ && it != recency_.begin()) {
    --it;
    if (it == recency_.begin()) break;
    const auto found = entries_.find(*it);
    if (found == entries_.end() || found->second->loading) continue;
    stats_.bytes -= found->second->bytes;
    ++stats_.evictions;
    entries_.erase(found);
    it = recency_.erase(it);
  }
}

std::shared_ptr<const NodePoints> NodeCache::get(const CellKey& key) {
  const NodeInfo* node = octree_->find(key);
  if (node == nullptr) return nullptr;
  bool must_load = false;
  const std::shared_ptr<Entry> entry = acquireLocked(*node, must_load);
  if (must_load) load(entry, *node);
  return wait(entry);
}

std::shared_ptr<const NodePoints> NodeCache::tryGet(const CellKey& key) {
  const NodeInfo* node = octree_->find(key);
  if (node == nullptr) return nullptr;
  bool must_load = false;
  const std::shared_ptr<Entry> entry = acquireLocked(*node, must_load);
  if (must_load) {
    loadInBackground(entry, *node);
    return nullptr;
  }
  const std::lock_guard lock(mutex_);
  return entry->loading || entry->error ? nullptr : entry->points;
}

std::shared_ptr<NodeCache::Entry> NodeCache::acquireLocked(const NodeInfo& node, bool& must_load) {
  const std::lock_guard lock(mutex_);
  return acquire(node, must_load);
}

void NodeCache::prefetch(const CellKey& key) {
  tryGet(key);
}

NodeCacheStats NodeCache::stats() const {
  const std::lock_guard lock(mutex_);
  NodeCacheStats stats = stats_;
  stats.nodes = entries_.size();
  return stats;
}

}  // namespace plumb::lod
