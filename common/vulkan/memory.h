// memory.h — device memory for many small buffers and images, taken from a few large blocks.
//
// A scene has dozens of small buffers (vertices, indices, uniforms per frame in flight); one
// vkAllocateMemory each is what the best-practices layer warns about: allocations are few
// (maxMemoryAllocationCount may be 4096) and slow, and each has a large minimum size on real
// GPUs. So memory is allocated in blocks of kBlockSize, one memory type each, and every buffer or
// image takes an aligned range of a block:
//  - first fit; a freed range merges with its free neighbours; a block left empty is given back;
//  - buffers and images never share a block (bufferImageGranularity needs no thought then);
//  - a resource larger than half a block gets an allocation (a block) of its own;
//  - host-visible blocks are mapped once, for their whole life.
#pragma once

#include "vk_check.h"

#include <map>
#include <memory>
#include <vector>

namespace lab {

class MemoryAllocator;

// A range of device memory; movable, given back to its allocator exactly once.
class Allocation {
public:
    Allocation() = default;
    ~Allocation() { reset(); }
    Allocation(const Allocation&) = delete;
    Allocation& operator=(const Allocation&) = delete;
    Allocation(Allocation&& other) noexcept { *this = std::move(other); }
    Allocation& operator=(Allocation&& other) noexcept;

    VkDeviceMemory memory() const { return memory_; }
    VkDeviceSize offset() const { return offset_; }
    void* mapped() const { return mapped_; }  // nullptr unless host-visible
    void reset();

private:
    friend class MemoryAllocator;
    MemoryAllocator* owner_ = nullptr;
    size_t block_ = 0;  // index into the owner's blocks
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize offset_ = 0;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

class MemoryAllocator {
public:
    static constexpr VkDeviceSize kBlockSize = VkDeviceSize(8) << 20;  // 8 MiB

    MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties);
    ~MemoryAllocator();  // gives back every block (all allocations must be gone by then)
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    // A range for a resource with these requirements, of the first memory type with `wanted`.
    // `image`: for an image (else a buffer) — the two never share a block.
    Allocation allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags wanted, bool image);

    uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const;
    size_t block_count() const;  // live blocks (for tests and curiosity)

private:
    friend class Allocation;
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;  // VK_NULL_HANDLE: slot unused
        VkDeviceSize size = 0;
        uint32_t type = 0;
        bool image = false;
        bool own = false;  // a single large resource: never shared
        void* mapped = nullptr;
        std::map<VkDeviceSize, VkDeviceSize> free;  // offset -> size, non-adjacent
    };
    size_t new_block(VkDeviceSize size, uint32_t type, bool image, bool own);
    void release(size_t block, VkDeviceSize offset, VkDeviceSize size);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_;
    std::vector<Block> blocks_;
};

}  // namespace lab
