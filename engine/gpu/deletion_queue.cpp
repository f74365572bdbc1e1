#include "engine/gpu/deletion_queue.h"

#include <utility>

namespace plumb::gpu {

DeletionQueue::~DeletionQueue() {
  for (auto& [value, destroy] : entries_) destroy();
}

void DeletionQueue::defer(std::uint64_t after_value, std::function<void()> destroy) {
  entries_.emplace(after_value, std::move(destroy));
}

std::size_t DeletionQueue::collect(std::uint64_t completed) {
  std::size_t ran = 0;
  for (auto it = entries_.begin(); it != entries_.end() && it->first <= completed; it = entries_.erase(it)) {
    it->second();
    ++ran;
  }
  return ran;
}

}  // namespace plumb::gpu
