// Block allocation of device memory (memory.h).
//
// allocate: the memory type; first fit over the free ranges of that type's blocks, the start
// rounded up to the alignment; a new block when none fits. release: the range goes back to its
// block's free list, merged with the free ranges on either side; an empty block is freed when
// another empty block of its type exists, or at once if it was a block of its own for one large
// request.

#include "engine/gpu/memory.h"

#include <cassert>
#include <iterator>
#include <string>
#include <utility>

#include "engine/gpu/device.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {
namespace {

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace

Allocation::~Allocation() {
  if (owner_) owner_->release(block_, offset_, size_);
}

Allocation::Allocation(Allocation&& other) noexcept
    : owner_(std::exchange(other.owner_, nullptr)),
      block_(other.block_),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      offset_(other.offset_),
      size_(other.size_),
      mapped_(std::exchange(other.mapped_, nullptr)) {}

Allocation& Allocation::operator=(Allocation&& other) noexcept {
  if (this != &other) {
    if (owner_) owner_->release(block_, offset_, size_);
    owner_ = std::exchange(other.owner_, nullptr);
    block_ = other.block_;
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    offset_ = other.offset_;
    size_ = other.size_;
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

MemoryAllocator::MemoryAllocator(const Device& device, VkDeviceSize block_size)
    : device_(device), block_size_(block_size) {}

MemoryAllocator::~MemoryAllocator() {
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (!blocks_[b]) continue;
    assert(blocks_[b]->used == 0 && "an Allocation outlives its allocator");
    freeBlock(b);
  }
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags properties) {
  const std::uint32_t type = device_.memoryType(requirements.memoryTypeBits, properties);
  const VkDeviceSize alignment = requirements.alignment > 0 ? requirements.alignment : 1;
  const VkDeviceSize size = requirements.size;
  const std::lock_guard lock(mutex_);

  std::size_t chosen = blocks_.size();
  VkDeviceSize at = 0;
  if (size <= block_size_) {
    for (std::size_t b = 0; b < blocks_.size() && chosen == blocks_.size(); ++b) {
      const Block* block = blocks_[b].get();
      if (!block || block->type != type || block->size > block_size_) continue;
      for (const auto& [offset, length] : block->free) {
        const VkDeviceSize start = alignUp(offset, alignment);
        if (start + size <= offset + length) {
          chosen = b;
          at = start;
          break;
        }
      }
    }
  }
  if (chosen == blocks_.size()) {
    chosen = newBlock(type, size <= block_size_ ? block_size_ : size);
    at = 0;
  }

  // Carve [at, at + size) out of the free range that holds it.
  Block& block = *blocks_[chosen];
  auto range = std::prev(block.free.upper_bound(at));
  const VkDeviceSize range_start = range->first, range_end = range->first + range->second;
  block.free.erase(range);
  if (at > range_start) block.free.emplace(range_start, at - range_start);
  if (at + size < range_end) block.free.emplace(at + size, range_end - (at + size));
  block.used += size;

  Allocation allocation;
  allocation.owner_ = this;
  allocation.block_ = chosen;
  allocation.memory_ = block.memory;
  allocation.offset_ = at;
  allocation.size_ = size;
  allocation.mapped_ = block.mapped ? block.mapped + at : nullptr;
  return allocation;
}

void MemoryAllocator::release(std::size_t index, VkDeviceSize offset, VkDeviceSize size) {
  const std::lock_guard lock(mutex_);
  Block& block = *blocks_[index];
  VkDeviceSize start = offset, end = offset + size;
  auto next = block.free.lower_bound(offset);
  if (next != block.free.end() && next->first == end) {
    end += next->second;
    next = block.free.erase(next);
  }
  if (next != block.free.begin()) {
    const auto previous = std::prev(next);
    if (previous->first + previous->second == start) {
      start = previous->first;
      block.free.erase(previous);
    }
  }
  block.free.emplace(start, end - start);
  block.used -= size;
  if (block.used > 0) return;
  bool another_empty = false;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (b != index && blocks_[b] && blocks_[b]->type == block.type && blocks_[b]->used == 0 &&
        blocks_[b]->size <= block_size_)
      another_empty = true;
  }
  if (another_empty || block.size > block_size_) freeBlock(index);
}

std::size_t MemoryAllocator::newBlock(std::uint32_t type, VkDeviceSize size) {
  // The device enables buffer device addresses, so any buffer may ask for one: every block can.
  VkMemoryAllocateFlagsInfo flags{};
  flags.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO;
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  info.pNext = &flags;
  info.allocationSize = size;
  info.memoryTypeIndex = type;
  auto block = std::make_unique<Block>();
  check(vkAllocateMemory(device_.handle(), &info, nullptr, &block->memory),
        "vkAllocateMemory of " + std::to_string(size >> 20) + " MiB");
  block->type = type;
  block->size = size;
  block->free.emplace(0, size);
  if (device_.memoryTypeFlags(type) & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    void* mapped = nullptr;
    const VkResult result = vkMapMemory(device_.handle(), block->memory, 0, VK_WHOLE_SIZE, 0, &mapped);
    if (result != VK_SUCCESS) vkFreeMemory(device_.handle(), block->memory, nullptr);
    check(result, "vkMapMemory");
    block->mapped = static_cast<std::byte*>(mapped);
  }
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (!blocks_[b]) {
      blocks_[b] = std::move(block);
      return b;
    }
  }
  blocks_.push_back(std::move(block));
  return blocks_.size() - 1;
}

void MemoryAllocator::freeBlock(std::size_t index) {
  Block& block = *blocks_[index];
  if (block.mapped) vkUnmapMemory(device_.handle(), block.memory);
  vkFreeMemory(device_.handle(), block.memory, nullptr);
  blocks_[index].reset();
}

std::size_t MemoryAllocator::blockCount() const {
  const std::lock_guard lock(mutex_);
  std::size_t count = 0;
  for (const auto& block : blocks_) count += block ? 1u : 0u;
  return count;
}

VkDeviceSize MemoryAllocator::bytesInUse() const {
  const std::lock_guard lock(mutex_);
  VkDeviceSize used = 0;
  for (const auto& block : blocks_) used += block ? block->used : 0;
  return used;
}

VkDeviceSize MemoryAllocator::bytesReserved() const {
  const std::lock_guard lock(mutex_);
  VkDeviceSize reserved = 0;
  for (const auto& block : blocks_) reserved += block ? block->size : 0;
  return reserved;
}

}  // namespace plumb::gpu
