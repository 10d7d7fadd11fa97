#pragma once
// Timestamp writes that are taken when their commands run, on every device.
//
// lavapipe (Mesa 22.3's llvmpipe) does not take a timestamp when the command buffer reaches it
// once a framebuffer has been bound on its queue (by any render pass before, such as the hardware
// baseline's): it bins the query into its rasterizer's scene and takes the time when that scene
// is rasterized, at the next flush. A top-of-pipe timestamp then lands after the passes that
// follow it (compute frames measured after the hardware baseline reported setup as nearly free),
// and a graphics frame's start lands after its vertex work. Every write but a top-of-pipe one
// flushes the scene before it, so a second write right after makes the first be taken at once.

#include <cstdint>

#include <vulkan/vulkan.h>

#include "compute/context.h"

namespace tessera {

/// Queries a timestamp pool needs for `stamps` timestamps that write_timestamp writes: on
/// devices of VK_PHYSICAL_DEVICE_TYPE_CPU twice as many (stamp i's flushing write goes to
/// i + stamps), elsewhere `stamps`.
uint32_t timestamp_pool_size(const Context& ctx, uint32_t stamps);

/// Records that a render pass is about to be recorded on ctx's queue, so that from now on
/// write_timestamp flushes on CPU devices. Call it before the frame's first timestamp.
void note_render_pass(const Context& ctx);

/// Records vkCmdWriteTimestamp(cmd, stage, pool, query). On a CPU device after
/// note_render_pass, it also writes query + `stamps` at bottom of pipe, a write that is never
/// read: its flush makes the first be taken now (on other devices, and before any render pass,
/// timestamps are taken when reached, and a flush would only add to the measured time: 0.13 ms
/// of one grid sphere's 0.95 ms frame on lavapipe at 128x128). `pool` holds
/// timestamp_pool_size(ctx, stamps) queries, all reset before, and `query` < `stamps` (checked).
void write_timestamp(const Context& ctx, VkCommandBuffer cmd, VkPipelineStageFlagBits stage,
                     VkQueryPool pool, uint32_t query, uint32_t stamps);

}  // namespace tessera
