#include "passes/taa.h"

#include <cmath>

#include "core/error.h"

namespace bounce {

using graph::Access;

void validate(const TaaSettings& settings) {
  if (settings.jitterPhases < 1 || settings.jitterPhases > 1024)
    fail("taa.jitterPhases {} is out of range (1 to 1024)", settings.jitterPhases);
  if (!(settings.blend > 0.0f && settings.blend <= 1.0f))
    fail("taa.blend {} is out of range (0, 1]", settings.blend);
  if (!(settings.clipSigma > 0.0f) || !std::isfinite(settings.clipSigma))
    fail("taa.clipSigma {} must be a finite number above 0", settings.clipSigma);
}

namespace {

// The i-th point of the radical-inverse sequence in `base` (Halton 1964), in [0, 1).
float radicalInverse(uint32_t i, uint32_t base) {
  float result = 0.0f;
  float scale = 1.0f;
  for (; i > 0; i /= base) {
    scale /= float(base);
    result += float(i % base) * scale;
  }
  return result;
}

}  // namespace

glm::vec2 taaJitter(uint64_t frame, uint32_t phases) {
  const uint32_t i = uint32_t(frame % phases) + 1;
  return glm::vec2(radicalInverse(i, 2), radicalInverse(i, 3)) - glm::vec2(0.5f);
}

// Clip x' = x - (2 jitter.x / width) w moves NDC x by -2 jitter.x / width, i.e. the image by
// -jitter.x pixels; likewise y (clip y and pixel rows both point down).
glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 jitter,
                                 glm::uvec2 resolution) {
  glm::mat4 m = viewProjection;
  const glm::vec2 shift = 2.0f * jitter / glm::vec2(resolution);
  for (int column = 0; column < 4; ++column) {
    m[column][0] -= shift.x * m[column][3];
    m[column][1] -= shift.y * m[column][3];
  }
  return m;
}

// The read-only inputs are sampled images (docs/architecture.md, "Sampled inputs").
TaaPass::TaaPass(vk::Context& context, const GpuScene& scene, const TaaSettings& settings)
    : settings_(settings),
      pass_(context, scene, "passes/taa", gpu::TAA_BINDING_COUNT, sizeof(gpu::TaaConstants), 1, {},
            bindingMask({gpu::TAA_BINDING_HDR, gpu::TAA_BINDING_VELOCITY, gpu::TAA_BINDING_DEPTH,
                         gpu::TAA_BINDING_PREVIOUS})) {}

HdrImage TaaPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                          const GBuffer& gbuffer, const HdrImage& hdr,
                          const std::optional<Exposure>& exposure) {
  graph::HistoryImage color =
      graph.createHistoryImage("taa.color", {VK_FORMAT_R16G16B16A16_SFLOAT});
  graph::PassBuilder pass = graph.addPass("taa", graph::QueueKind::Compute);
  pass.write(color.current, Access::StorageWrite, gpu::TAA_BINDING_CURRENT)
      .read(frame.constants, Access::StorageRead)
      .read(hdr.radiance, Access::SampledRead, gpu::TAA_BINDING_HDR)
      .read(gbuffer.velocity, Access::SampledRead, gpu::TAA_BINDING_VELOCITY)
      .read(gbuffer.depth.current, Access::SampledRead, gpu::TAA_BINDING_DEPTH)
      .read(color.previous, Access::SampledRead, gpu::TAA_BINDING_PREVIOUS);
  if (exposure) pass.read(exposure->state, Access::StorageRead);
  pass.record([this, frame, exposure, color](VkCommandBuffer cmd, const graph::PassResources& r) {
    gpu::TaaConstants constants{};
    constants.frame = frame.constantsAddress;
    if (exposure) constants.exposureState = r.buffer(exposure->state).address;
    constants.blend = settings_.blend;
    constants.clipSigma = settings_.clipSigma;
    constants.historyValid = r.historyValid(color) ? 1u : 0u;
    pass_.bind(cmd, constants, r);
    vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                          gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
  });
  return {color.current};
}

}  // namespace bounce
