// The slot through which a diffuse-GI system plugs into the hybrid frame (DESIGN.md §4).
// The frame declares the GBuffer and scene resources, hands their handles to the system in
// GiInputs, and the system declares its own passes on the same frame graph; they end by
// writing `gi.diffuse`, which `composite` reads.
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
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/shadows_denoise.h"
#include "shared/hybrid_frame_io.h"

namespace bounce {

class ClipmapCache;
class GpuScene;
struct Scene;
namespace vk {
class Context;
}

// What a GI system reads from the frame: the frame's constants and scene arrays, the GBuffer and
// the sun's denoised visibility.
struct GiInputs {
  FrameContext frame;
  GBuffer gbuffer;
  Shadows shadows;
};

// What a GI system produces.
struct DiffuseGiOutput {
  graph::ImageHandle diffuse;  // gi.diffuse (see above)
};

// One numbered fact about the last frame for `--timings` JSON (e.g. live cache cells).
struct GiStatistic {
  std::string name;
  double value = 0.0;
};

class DiffuseGi {
 public:
  virtual ~DiffuseGi() = default;
  // Declares this frame's GI passes, the last of which writes gi.diffuse (see above).
  virtual DiffuseGiOutput declare(graph::FrameGraph& graph, const GiInputs& inputs) = 0;
  // The image a system creates for gi.diffuse.
  static graph::ImageHandle createOutput(graph::FrameGraph& graph) {
    return graph.createImage("gi.diffuse", {VK_FORMAT_R16G16B16A16_SFLOAT});
  }
  // After the frame's submission has completed: read back statistics, advance counters.
  virtual void afterFrame() {}
  // Facts about the last completed frame, for `--timings` JSON and the README tables.
  virtual std::vector<GiStatistic> statistics() const { return {}; }
  // A camera cut: forget temporal state that is not in frame-graph history images.
  virtual void resetHistory() {}
  // A lighting cut (the sun jumped, HybridFrame::setSunAndSky): the view's history stays valid
  // but the light it holds does not; rebuild it quickly.
  virtual void lightingCut() {}
  // The world-space radiance cache the system keeps up to date this frame, which other passes
  // (reflections-trace) may look up after declare(); nullptr when it has none.
  virtual const ClipmapCache* clipmapCache() const { return nullptr; }
};

}  // namespace bounce
