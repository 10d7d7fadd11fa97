#pragma once
// The renderer's internal interface, for the parts of Tessera that draw with its resources or
// inspect them: the graphics-pipeline baseline (compute/baselines/) and tests. Applications use
// compute/renderer.h only; this follows the renderer's internals and changes with them.

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include "compute/gpu_memory.h"
#include "compute/passes.h"
#include "compute/renderer.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

class RendererInternal {
 public:
  /// What a frame recorded outside the renderer's own passes draws with. Handles stay valid
  /// until the next call on the renderer that changes the scene or the image size.
  struct Frame {
    VkDescriptorSet set = VK_NULL_HANDLE;      // the shared set (bindings of compute/passes.h)
    VkPipelineLayout layout = VK_NULL_HANDLE;  // its layout, push constants GpuBatch, kShaderStages
    VkImage hdr_image = VK_NULL_HANDLE;        // the HDR image (RGBA16F, layout GENERAL, also a
                                               // copy destination) the resolve pass reads
    uint64_t images_generation = 0;            // changes whenever the output images are recreated
    uint32_t width = 0, height = 0;
    VkBuffer indices = VK_NULL_HANDLE;        // the scene's uint32 indices (index-buffer usage too)
    std::span<const gpu::GpuObject> objects;  // the scene's objects in slot order (the GPU's)
    glm::vec3 background{0.0f};  // as the HDR image holds it: pre-exposed, clamped to 65504
    CullMode cull = CullMode::back;
    /// Level of detail (FrameSettings::lod automatic, and the scene has triangles): record_lod
    /// must run before drawing; it writes a VkDrawIndexedIndirectCommand per object slot into
    /// `lod_draws` (indexed draws of one instance, first instance the slot).
    bool lod = false;
    VkBuffer lod_draws = VK_NULL_HANDLE;
    // The specialization constants of the compute path's shading pass for this frame: light
    // counts, texture maps, environment, uv sets (or the generic pipeline's, without
    // RendererOptions::specialize_lights), for shaders that include the same lighting code.
    Specialization shading{};
  };

  /// Prepares a frame of `settings` as render() does, without recording any pass: checks the
  /// size, (re)allocates the images and buffers, updates the descriptor set and writes the
  /// frame constants. Throws Error as render() does (no scene, a size the device cannot hold).
  static Frame prepare_frame(Renderer& renderer, const FrameSettings& settings);

  /// Records what the frame needs computed once (DFG tables, the environment), as render()
  /// does. The shared set must be bound at the compute bind point.
  static void record_precomputation(Renderer& renderer, VkCommandBuffer cmd,
                                    const FrameSettings& settings);

  /// Records the level-of-detail passes (Frame::lod), which choose each object's level into
  /// the objects and the draws of Frame::lod_draws, then a barrier making them visible to
  /// indirect draws and vertex shaders. Binds the shared set at the compute bind point.
  static void record_lod(Renderer& renderer, VkCommandBuffer cmd);

  /// Records the resolve pass (HDR image to display image; binds its pipeline and the shared
  /// set at the compute bind point), then a barrier making its writes visible to transfers.
  static void record_resolve(Renderer& renderer, VkCommandBuffer cmd);

  /// The shared descriptor set, its layout, and a number that changes whenever the renderer
  /// rewrites the set's descriptors (a new scene's buffers, a new size), so that a set copied
  /// from it knows when to copy again. Valid after the first render().
  struct SharedSet {
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    uint64_t generation = 0;
  };
  static SharedSet shared_set(const Renderer& renderer);

  /// Records the resolve pass of the last frame into the storage image that `set` binds at
  /// TS_BINDING_LDR_IMAGE (an R8G8B8A8_UNORM view in GENERAL, the frame's size; `set` has the
  /// shared set's layout and its other bindings), storing B, G, R, A where `bgra`. Binds the
  /// pipeline and `set` at the compute bind point; the caller orders the HDR image's writes
  /// before it and the target's use after it. For RendererOptions::resolve off.
  static void record_resolve_into(Renderer& renderer, VkCommandBuffer cmd, VkDescriptorSet set,
                                  bool bgra);

  /// The renderer's buffer at `binding` (TS_BINDING_* of a buffer the renderer owns; empty
  /// before the first frame that allocates it).
  static const Buffer& buffer(const Renderer& renderer, uint32_t binding);

  /// The context the renderer was created with.
  static Context& context(const Renderer& renderer);
};

}  // namespace tessera
