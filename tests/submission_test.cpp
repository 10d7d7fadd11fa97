// submit_and_wait (compute/gpu_memory.h) records every submission of a context into one command
// buffer and waits on one fence (Context::submission): a submission after many others, and after
// one whose recording threw, still runs what it recorded, and the validation layer (on in this
// suite) reports nothing. The buffer's contents come back through download_buffer, itself a
// submission.
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "compute/gpu_memory.h"
#include "compute/readback.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

using Submission = test::VulkanTest;

// Fills `buffer` (4-byte words) with `value` in one submission.
void fill(const Context& ctx, const Buffer& buffer, uint32_t value) {
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, buffer.buffer, 0, VK_WHOLE_SIZE, value);
  });
}

TEST_F(Submission, EachOfManySubmissionsRunsWhatItRecorded) {
  const Context& ctx = context();
  Buffer buffer =
      create_buffer(ctx, 64, VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                    MemoryKind::device);
  for (uint32_t i = 1; i <= 50; ++i) {
    fill(ctx, buffer, i * 0x01010101u);
    EXPECT_EQ(download_buffer<uint32_t>(ctx, buffer, 16),
              std::vector<uint32_t>(16, i * 0x01010101u))
        << "submission " << i;
  }
  destroy_buffer(ctx, buffer);
}

TEST_F(Submission, ARecordingThatThrowsLeavesTheContextUsable) {
  const Context& ctx = context();
  Buffer buffer =
      create_buffer(ctx, 64, VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                    MemoryKind::device);
  fill(ctx, buffer, 7);
  // Throws halfway through recording: the fill it recorded must never run.
  EXPECT_THROW(submit_and_wait(ctx,
                               [&](VkCommandBuffer cmd) {
                                 vkCmdFillBuffer(cmd, buffer.buffer, 0, VK_WHOLE_SIZE, 99);
                                 throw std::runtime_error("recording failed");
                               }),
               std::runtime_error);
  EXPECT_EQ(download_buffer<uint32_t>(ctx, buffer, 16), std::vector<uint32_t>(16, 7u));
  fill(ctx, buffer, 11);
  EXPECT_EQ(download_buffer<uint32_t>(ctx, buffer, 16), std::vector<uint32_t>(16, 11u));
  destroy_buffer(ctx, buffer);
}

}  // namespace
}  // namespace tessera
