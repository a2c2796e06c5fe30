// test_memory.cpp — the sub-allocator (common/vulkan/memory.h) on a real device, validation on.
//
// Ranges are aligned and disjoint, small resources share one block, a large one gets its own,
// freed ranges are reused, and every block is given back once its last range is freed (so memory
// does not grow over scene reloads and window resizes).
#include "memory.h"
#include "vk_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace {

struct Range {
    VkDeviceMemory memory;
    VkDeviceSize begin, end;
};

VkMemoryRequirements requirements(const lab::VulkanContext& vk, VkDeviceSize size, VkDeviceSize alignment) {
    VkMemoryRequirements req{};
    req.size = size;
    req.alignment = alignment;
    req.memoryTypeBits = 1u << vk.find_memory_type(~0u, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
    return req;
}

TEST(Memory, SmallRangesShareABlockAlignedAndDisjoint) {
    int messages = 0;
    {
        lab::ContextOptions options;
        options.validate = true;
        options.message_count = &messages;
        lab::VulkanContext vk(options);
        lab::MemoryAllocator& allocator = vk.allocator();
        const size_t blocks_before = allocator.block_count();
        std::vector<lab::Allocation> live;
        const VkDeviceSize sizes[] = {24, 768, 4096, 100, 65536, 3, 256};
        const VkDeviceSize alignments[] = {16, 256, 64, 4, 1024, 1, 256};
        for (int i = 0; i < 7; ++i)
            live.push_back(allocator.allocate(requirements(vk, sizes[i], alignments[i]),
                                              VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, false));
        EXPECT_EQ(allocator.block_count(), blocks_before + 1) << "seven small buffers, one block";
        std::vector<Range> ranges;
        for (int i = 0; i < 7; ++i) {
            EXPECT_EQ(live[i].offset() % alignments[i], 0u) << i;
            EXPECT_EQ(live[i].memory(), live[0].memory());
            ASSERT_NE(live[i].mapped(), nullptr);  // host-visible: mapped at its offset
            EXPECT_EQ(static_cast<char*>(live[i].mapped()) - static_cast<char*>(live[0].mapped()),
                      std::ptrdiff_t(live[i].offset()) - std::ptrdiff_t(live[0].offset()));
            ranges.push_back({live[i].memory(), live[i].offset(), live[i].offset() + sizes[i]});
        }
        for (size_t a = 0; a < ranges.size(); ++a)
            for (size_t b = a + 1; b < ranges.size(); ++b)
                EXPECT_TRUE(ranges[a].end <= ranges[b].begin || ranges[b].end <= ranges[a].begin) << a << " " << b;

        // A freed range is reused by the next allocation that fits.
        const VkDeviceSize freed = live[4].offset();
        live[4].reset();
        lab::Allocation again =
            allocator.allocate(requirements(vk, 65536, 1024), VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, false);
        EXPECT_EQ(again.offset(), freed);

        // Something larger than half a block has a block of its own.
        lab::Allocation big = allocator.allocate(requirements(vk, lab::MemoryAllocator::kBlockSize, 256),
                                                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, false);
        EXPECT_NE(big.memory(), live[0].memory());
        EXPECT_EQ(big.offset(), 0u);
        EXPECT_EQ(allocator.block_count(), blocks_before + 2);

        // Everything freed (in any order, moved around first): every block is given back.
        lab::Allocation moved = std::move(live[2]);
        live.clear();
        again.reset();
        EXPECT_EQ(allocator.block_count(), blocks_before + 2) << "`moved` still holds a range";
        moved.reset();
        big.reset();
        EXPECT_EQ(allocator.block_count(), blocks_before);
    }
    EXPECT_EQ(messages, 0) << "validation messages (see stderr)";
}

TEST(Memory, BuffersAndImagesNeverShareABlock) {
    lab::VulkanContext vk(lab::ContextOptions{});
    lab::MemoryAllocator& allocator = vk.allocator();
    const uint32_t type = vk.find_memory_type(~0u, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkMemoryRequirements req{1024, 256, 1u << type};
    lab::Allocation buffer = allocator.allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false);
    lab::Allocation image = allocator.allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, true);
    EXPECT_NE(buffer.memory(), image.memory());
}

}  // namespace
