// What every pass of the hybrid frame reads: this frame's constants and the scene arrays that
// move, as `scene-update` declared them (passes/scene_update.h).
#pragma once
#include <vulkan/vulkan.h>

#include "graph/handles.h"
#include "shared/hybrid_frame_io.h"

namespace bounce {

struct FrameContext {
  graph::BufferHandle constants;  // frame-constants: gpu::FrameConstants
  VkDeviceAddress constantsAddress = 0;
  const gpu::FrameConstants* hostConstants = nullptr;  // the CPU copy of this frame's constants
  graph::BufferHandle instances;                       // scene.instances (moving objects)
  graph::BufferHandle previousInstances;               // scene.previous-instances
  graph::BufferHandle tlas;                            // scene.tlas-nodes
  VkExtent2D resolution{};                             // render resolution
  // This frame follows a lighting cut (the sun jumped): temporal passes drop the light they
  // hold, while the view's history stays valid.
  bool lightingCut = false;

  // The push constants of the frame's per-pixel passes.
  gpu::HybridPassConstants passConstants(bool historyValid = false) const {
    return {constantsAddress, historyValid ? 1u : 0u, 0u};
  }
};

}  // namespace bounce
