// The slot through which a diffuse-GI system plugs into the hybrid frame (DESIGN.md §4).
// HybridFrame::recordFrame declares the GBuffer and scene resources, hands their handles to the
// system in FrameInputs, and the system declares its own passes on the same frame graph; they
// must end by writing `gi.diffuse`, which `composite` reads.
//
// What `gi.diffuse` holds: at each pixel, the outgoing diffuse radiance per unit albedo,
// i.e. irradiance / pi at the primary hit (composite multiplies it by the diffuse albedo).
// rgba16f at render resolution; alpha is free for the system (e.g. a confidence).
//
// A system's GPU memory is made in its constructor or at its first declare(); later frames
// allocate nothing (DESIGN.md: no per-frame allocation).
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "graph/frame_graph.h"
#include "render/settings.h"
#include "shared/hybrid_frame_io.h"

namespace bounce {

class GpuScene;
struct Scene;
namespace vk {
class Context;
}

// This frame's resources, as the hybrid frame declared them.
struct FrameInputs {
  graph::BufferHandle frameConstants;  // gpu::FrameConstants (camera, sun, sky, resolution, ...)
  VkDeviceAddress frameConstantsAddress = 0;
  const gpu::FrameConstants* constants = nullptr;  // the CPU copy of this frame's constants
  graph::BufferHandle instances;          // scene.instances (moving objects)
  graph::BufferHandle previousInstances;  // scene.previous-instances
  graph::BufferHandle tlas;               // scene.tlas-nodes
  graph::ImageHandle baseColor;           // gbuffer.base-color: rgb base colour, a metallic
  graph::ImageHandle normals;             // gbuffer.normals: xy shading, zw geometric (octahedral)
  graph::HistoryImage depth;              // gbuffer.depth: view depth, current and previous
  graph::ImageHandle uv;                  // gbuffer.uv
  graph::ImageHandle velocity;            // gbuffer.velocity: pixels moved since last frame
  graph::ImageHandle emissive;            // gbuffer.emissive: rgb emission, a roughness
  graph::ImageHandle flags;               // gbuffer.flags: GBUFFER_FLAG_*
  graph::ImageHandle sunVisibility;       // shadows.visibility (current): denoised, full res
  VkExtent2D resolution{};
};

// One numbered fact about the last frame for `--timings` JSON (e.g. live cache cells).
struct GiStatistic {
  std::string name;
  double value = 0.0;
};

class DiffuseGi {
 public:
  virtual ~DiffuseGi() = default;
  // Declares this frame's GI passes, which must write `output` (gi.diffuse, see above).
  virtual void declare(graph::FrameGraph& graph, const FrameInputs& inputs,
                       graph::ImageHandle output) = 0;
  // After the frame's submission has completed: read back statistics, advance counters.
  virtual void afterFrame() {}
  // Facts about the last completed frame, for `--timings` JSON and the README tables.
  virtual std::vector<GiStatistic> statistics() const { return {}; }
  // A camera cut: forget temporal state that is not in frame-graph history images.
  virtual void resetHistory() {}
  // A lighting cut (the sun jumped, HybridFrame::setSunAndSky): the view's history stays valid
  // but the light it holds does not; rebuild it quickly.
  virtual void lightingCut() {}
};

// The system for `settings.gi`; nullptr for GiMode::None (gi.diffuse then stays zero).
std::unique_ptr<DiffuseGi> makeDiffuseGi(vk::Context& context, GpuScene& gpuScene,
                                         const Scene& scene, const HybridSettings& settings);

}  // namespace bounce
