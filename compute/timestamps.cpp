#include "compute/timestamps.h"

#include "core/check.h"

namespace tessera {
namespace {

bool cpu_device(const Context& ctx) {
  return ctx.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

}  // namespace

uint32_t timestamp_pool_size(const Context& ctx, uint32_t stamps) {
  return cpu_device(ctx) ? 2 * stamps : stamps;
}

void note_render_pass(const Context& ctx) {
  ctx.render_pass_recorded = true;
}

void write_timestamp(const Context& ctx, VkCommandBuffer cmd, VkPipelineStageFlagBits stage,
                     VkQueryPool pool, uint32_t query, uint32_t stamps) {
  TESSERA_CHECK(query < stamps);
  vkCmdWriteTimestamp(cmd, stage, pool, query);
  if (cpu_device(ctx) && ctx.render_pass_recorded)
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, query + stamps);
}

}  // namespace tessera
