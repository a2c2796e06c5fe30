#include "memory.h"

#include <utility>

namespace lab {

// ---------------------------------------------------------------- Allocation

Allocation& Allocation::operator=(Allocation&& other) noexcept {
    if (this != &other) {
        reset();
        owner_ = std::exchange(other.owner_, nullptr);
        block_ = other.block_;
        memory_ = std::exchange(other.memory_, VkDeviceMemory(VK_NULL_HANDLE));
        offset_ = other.offset_;
        size_ = other.size_;
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void Allocation::reset() {
    if (owner_) owner_->release(block_, offset_, size_);
    owner_ = nullptr;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
}

// ---------------------------------------------------------------- MemoryAllocator

namespace {
VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
    return (value + alignment - 1) / alignment * alignment;  // alignment: a power of two, or 1
}
}  // namespace

MemoryAllocator::MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties)
    : device_(device), properties_(properties) {}

MemoryAllocator::~MemoryAllocator() {
    for (Block& b : blocks_)
        if (b.memory) vkFreeMemory(device_, b.memory, nullptr);  // unmapped implicitly
}

uint32_t MemoryAllocator::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const {
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (properties_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    throw VulkanError("no Vulkan memory type with the requested properties");
}

size_t MemoryAllocator::block_count() const {
    size_t n = 0;
    for (const Block& b : blocks_) n += b.memory != VK_NULL_HANDLE;
    return n;
}

size_t MemoryAllocator::new_block(VkDeviceSize size, uint32_t type, bool image, bool own) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    Block block;
    VK_CHECK(vkAllocateMemory(device_, &info, nullptr, &block.memory));
    block.size = size;
    block.type = type;
    block.image = image;
    block.own = own;
    block.free[0] = size;
    if (properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        const VkResult mapped = vkMapMemory(device_, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped);
        if (mapped != VK_SUCCESS) {
            vkFreeMemory(device_, block.memory, nullptr);
            throw_vk_error(mapped, "vkMapMemory", __FILE__, __LINE__);
        }
    }
    for (size_t i = 0; i < blocks_.size(); ++i)  // reuse a slot a freed block left
        if (!blocks_[i].memory) {
            blocks_[i] = std::move(block);
            return i;
        }
    blocks_.push_back(std::move(block));
    return blocks_.size() - 1;
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags wanted, bool image) {
    const uint32_t type = find_memory_type(req.memoryTypeBits, wanted);
    const VkDeviceSize alignment = req.alignment ? req.alignment : 1;

    // First fit in a shared block of this type and kind.
    size_t chosen = blocks_.size();
    VkDeviceSize offset = 0;
    if (req.size <= kBlockSize / 2) {
        for (size_t i = 0; i < blocks_.size() && chosen == blocks_.size(); ++i) {
            const Block& b = blocks_[i];
            if (!b.memory || b.own || b.type != type || b.image != image) continue;
            for (const auto& [start, length] : b.free) {
                const VkDeviceSize aligned = align_up(start, alignment);
                if (aligned + req.size <= start + length) {
                    chosen = i;
                    offset = aligned;
                    break;
                }
            }
        }
        if (chosen == blocks_.size()) chosen = new_block(kBlockSize, type, image, /*own=*/false);
    } else {
        chosen = new_block(req.size, type, image, /*own=*/true);
    }

    // Cut [offset, offset + size) out of the free range that holds it.
    Block& b = blocks_[chosen];
    auto range = std::prev(b.free.upper_bound(offset));
    const VkDeviceSize start = range->first, end = range->first + range->second;
    b.free.erase(range);
    if (start < offset) b.free[start] = offset - start;
    if (offset + req.size < end) b.free[offset + req.size] = end - (offset + req.size);

    Allocation a;
    a.owner_ = this;
    a.block_ = chosen;
    a.memory_ = b.memory;
    a.offset_ = offset;
    a.size_ = req.size;
    a.mapped_ = b.mapped ? static_cast<char*>(b.mapped) + offset : nullptr;
    return a;
}

void MemoryAllocator::release(size_t index, VkDeviceSize offset, VkDeviceSize size) {
    Block& b = blocks_[index];
    // Insert the range, then merge it with the free range after it and the one before it.
    auto it = b.free.emplace(offset, size).first;
    if (auto next = std::next(it); next != b.free.end() && offset + size == next->first) {
        it->second += next->second;
        b.free.erase(next);
    }
    if (it != b.free.begin()) {
        auto prev = std::prev(it);
        if (prev->first + prev->second == it->first) {
            prev->second += it->second;
            b.free.erase(it);
        }
    }
    // Entirely free: give the block back (a window resize or a scene reload frees whole sets of
    // resources, and memory must not grow with them).
    if (b.free.size() == 1 && b.free.begin()->first == 0 && b.free.begin()->second == b.size) {
        vkFreeMemory(device_, b.memory, nullptr);
        b = Block{};
    }
}

}  // namespace lab
