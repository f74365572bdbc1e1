#pragma once
// Destroys what frames in flight may still use only once the GPU is done with it. Each entry
// waits for a timeline value: that of the last submission that used the object (the frame
// counter the renderer signals on its timeline semaphore). collect(completed), once per frame
// with the semaphore's value, runs the entries whose value has been reached, in the order they
// were deferred. Not thread-safe: the render thread owns it.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>

namespace plumb::gpu {

class DeletionQueue {
 public:
  DeletionQueue() = default;
  // Runs what is left: the owner waits for the device to be idle first.
  ~DeletionQueue();
  DeletionQueue(const DeletionQueue&) = delete;
  DeletionQueue& operator=(const DeletionQueue&) = delete;

  void defer(std::uint64_t after_value, std::function<void()> destroy);
  // Runs the entries of values up to `completed`; returns how many ran.
  std::size_t collect(std::uint64_t completed);
  std::size_t pending() const { return entries_.size(); }

 private:
  std::multimap<std::uint64_t, std::function<void()>> entries_;  // equal values keep their order
};

}  // namespace plumb::gpu
