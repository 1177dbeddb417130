// VulkanDevice's submissions: a command buffer goes back to the pool whatever its recording does.
#include "gpu_test_support.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "gpu/gpu_buffer.h"

namespace vitrum::testing {
namespace {

struct RecordingFailed : std::runtime_error {
    RecordingFailed() : std::runtime_error("recording failed") {}
};

// Fills `buffer` with `value` on the device and makes the writes visible to the host.
void fillOnDevice(VulkanDevice& device, const GpuBuffer& buffer, std::uint32_t value) {
    device.submitAndWait([&](VkCommandBuffer commands) {
        vkCmdFillBuffer(commands, buffer.buffer(), 0, VK_WHOLE_SIZE, value);
        const VkMemoryBarrier barrier{
            .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
        };
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
    });
}

// A device of its own, so that what it leaves behind at its destruction is its own: a `record`
// that throws halfway through its commands, many times over, then a real submission.
TEST(VulkanDevice, ARecordThatThrowsLeavesNoCommandBufferBehind) {
    const std::uint32_t messagesBefore = testDevice().validationMessages();
    {
        VulkanDevice device(std::to_string(testDevice().description().index));
        GpuBuffer buffer(device, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, "filled buffer", MemoryUse::Readback);
        ASSERT_NE(buffer.mapped(), nullptr);
        std::uint32_t* words = buffer.as<std::uint32_t>();
        std::fill(words, words + 64, 0u);
        ASSERT_EQ(device.commandBuffersInUse(), 0u);
        for (int i = 0; i < 1000; ++i) {
            EXPECT_THROW(device.submitAndWait([&](VkCommandBuffer commands) {
                vkCmdFillBuffer(commands, buffer.buffer(), 0, VK_WHOLE_SIZE, 0xDEADBEEFu);
                throw RecordingFailed();
            }),
                         RecordingFailed);
            ASSERT_EQ(device.commandBuffersInUse(), 0u) << "after " << i + 1 << " throwing records";
        }
        // None of the abandoned fills ran, and the device still runs submissions.
        EXPECT_EQ(std::vector<std::uint32_t>(words, words + 64), std::vector<std::uint32_t>(64, 0u));
        fillOnDevice(device, buffer, 0x12345678u);
        EXPECT_EQ(std::vector<std::uint32_t>(words, words + 64), std::vector<std::uint32_t>(64, 0x12345678u));
        EXPECT_EQ(device.commandBuffersInUse(), 0u);
    }
    EXPECT_EQ(testDevice().validationMessages(), messagesBefore) << "validation messages, destruction included";
}

}  // namespace
}  // namespace vitrum::testing
