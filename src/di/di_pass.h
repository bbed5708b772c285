// What the passes of the ReSTIR DI chain share: the pass shape, this frame's facts and the
// GBuffer inputs every pass binds (shared/restir_di_io.h).
#pragma once
#include <optional>
#include <string>

#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "shared/restir_di_io.h"

namespace bounce {

// One compute pass of the chain: scene at set 0, storage images at set 1 (DI_BINDING_* and the
// pass's own), gpu::DiPassConstants in push constants, one thread per pixel.
class DiPass : public ComputePass {
 public:
  DiPass(vk::Context& context, const GpuScene& scene, const std::string& shader,
         uint32_t imageCount, std::span<const uint32_t> specialization = {})
      : ComputePass(context, scene, shader, imageCount, sizeof(gpu::DiPassConstants), 1,
                    specialization) {}

  // Covers `extent` with groups of groupSide^2 threads (the shader's local size).
  void record(VkCommandBuffer cmd, const graph::PassResources& resources,
              const gpu::DiPassConstants& constants, VkExtent2D extent,
              uint32_t groupSide = gpu::DI_GROUP_SIZE) {
    bind(cmd, constants, resources);
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, groupSide, groupSide);
  }
};

// This frame's facts every pass reads; copied into the record callbacks.
struct DiFrame {
  FrameContext frame;
  GBuffer gbuffer;
  VkDeviceAddress constants = 0;  // gpu::DiConstants
  graph::BufferHandle lights;     // di.lights: the light tables every pass reads
  bool dropHistory = false;       // di-temporal ignores its history (a light switched on)
  // di-light-grid's slots (DiConstants::lightGrid's), which di-generate-candidates reads; none
  // without the grid.
  std::optional<graph::BufferHandle> lightGrid;
  // di.reservoir-final: di-shade writes its current side, di-temporal reads the previous one;
  // none without reuse (--di uniform).
  std::optional<graph::HistoryImage> finalReservoirs;

  gpu::DiPassConstants passConstants(bool historyValid = false) const {
    return {frame.constantsAddress, constants, historyValid ? 1u : 0u, 0u};
  }
};

// A reservoir image (restir_di_io.h: light, u, W, M in one RGBA32UI texel).
constexpr VkFormat kDiReservoirFormat = VK_FORMAT_R32G32B32A32_UINT;

// Declares the frame constants and the GBuffer images at DI_BINDING_* on `pass`.
graph::PassBuilder& readDiGBuffer(graph::PassBuilder& pass, const DiFrame& f);

}  // namespace bounce
