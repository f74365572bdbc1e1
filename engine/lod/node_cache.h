#pragma once
// A thread-safe cache of loaded octree nodes with a memory budget and least-recently-used
// eviction. Nodes load on the calling thread (get) or as background jobs (prefetch); a node
// that several threads ask for at once is loaded once. Evicted nodes stay valid for whoever
// still holds them (shared ownership); the budget bounds what the cache itself keeps.

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "engine/lod/octree.h"

namespace plumb::lod {

struct NodeCacheStats {
  std::uint64_t hits = 0;
  std::uint64_t misses = 0;      // loads started
  std::uint64_t bytes_read = 0;  // of the files, by those loads (NodeInfo::bytes)
  std::uint64_t evictions = 0;
  std::uint64_t bytes = 0;  // held by the cache now
  std::uint64_t nodes = 0;
};

class NodeCache {
 public:
  NodeCache(std::shared_ptr<const Octree> octree, std::size_t budget_bytes);
  // Waits for background loads to finish.
  ~NodeCache();
  NodeCache(const NodeCache&) = delete;
  NodeCache& operator=(const NodeCache&) = delete;

  const Octree& octree() const { return *octree_; }

  // The points of `key`, loading them on this thread if needed; null when the octree has no
  // such node. Rethrows the load's plumb::Error (a corrupt node) to every caller that waits.
  std::shared_ptr<const NodePoints> get(const CellKey& key);

  // The points of `key` if they are loaded already; otherwise starts a background load and
  // returns null. Never blocks on disk.
  std::shared_ptr<const NodePoints> tryGet(const CellKey& key);

  // Starts a background load of `key` unless it is loaded or loading.
  void prefetch(const CellKey& key);

  NodeCacheStats stats() const;

  // Where background loads run: by default oneTBB tasks of the cache's own; an app with a job
  // system passes a runner that submits the work at its streaming priority. The runner must run
  // every piece of work it is given, even when cancelled (the cache waits for them when it is
  // destroyed). Set it before the first tryGet or prefetch.
  using BackgroundRunner = std::function<void(std::function<void()> work)>;
  void setBackgroundRunner(BackgroundRunner runner);

 private:
  struct Entry;
  // Finds or creates the entry for `node`; returns whether this caller must load it.
  std::shared_ptr<Entry> acquire(const NodeInfo& node, bool& must_load);        // mutex_ held
  std::shared_ptr<Entry> acquireLocked(const NodeInfo& node, bool& must_load);  // takes mutex_
  void load(const std::shared_ptr<Entry>& entry, const NodeInfo& node);
  void loadInBackground(const std::shared_ptr<Entry>& entry, const NodeInfo& node);
  std::shared_ptr<const NodePoints> wait(const std::shared_ptr<Entry>& entry);
  void evictOverBudget();

  std::shared_ptr<const Octree> octree_;
  std::size_t budget_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable loaded_;
  std::list<CellKey> recency_;  // most recent first
  std::unordered_map<CellKey, std::shared_ptr<Entry>, CellKeyHash> entries_;
  NodeCacheStats stats_;
  struct Background;  // the oneTBB task group of background loads
  std::unique_ptr<Background> background_;
};

}  // namespace plumb::lod
