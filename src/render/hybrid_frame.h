// The hybrid frame without GI (DESIGN.md §4; seed 000's mobile hybrid renderer): scene-update,
// vbuffer, gbuffer, shadows-trace, shadows-denoise, sky, composite, tonemap, declared on the
// frame graph once per frame by recordFrame(). Resources are created by the first frame (and a
// resize); later frames only update the frame constants and record.
//
//   HybridFrame frame(context, gpuScene, scene, settings);
//   frame.requestDebugView("composite");      // any pass or resource by name
//   for (...) frame.render(camera);           // submits and waits; returns per-pass timings
//   ImageRGBA32F hdr = frame.debugViewImage("composite");
#pragma once
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <memory>

#include "gi/diffuse_gi.h"
#include "graph/frame_graph.h"
#include "passes/image_pass.h"
#include "render/gpu_scene.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "shared/hybrid_frame_io.h"
#include "tools/image_io.h"
#include "vk/gpu_timer.h"
#include "vk/graphics_pipeline.h"

namespace bounce {

// World to Vulkan clip space for the camera that shoots rays through pixel centres
// (shared/camera.h): y down, reversed Z with an infinite far plane, depth = near / view depth.
glm::mat4 viewProjection(const gpu::GpuCamera& camera, float nearPlane);

// Tells a lighting cut from motion (HybridSettings::lightingCutDegrees): from one sun and sky
// to the next, the lit sun turned by more than cutDegrees, or the sun's irradiance or the
// sky's radiance changed by more than half of the brightest seen so far (so that a sun
// fading out at dusk, step by small step, is motion, and switching it off is a cut), or the
// sky model changed. cutDegrees < 0: never a cut.
class LightingCutDetector {
 public:
  LightingCutDetector(const Sun& sun, const Sky& sky, float cutDegrees);
  // Takes the next sun and sky; whether they are a cut from the last ones.
  bool next(const Sun& sun, const Sky& sky);

 private:
  Sun sun_;
  Sky sky_;
  float cutDegrees_;
  float brightestSun_;  // irradiance, W/m^2
  float brightestSky_;  // radiance summed over r, g, b
};

class HybridFrame {
 public:
  // `scene` must be the one `gpuScene` was built from.
  HybridFrame(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
              const HybridSettings& settings);

  // Time-varying scene state for the next render() (issue 4; scene/animation.h evaluates it).
  // Instances: one objectToWorld per scene instance; `scene-update` uploads them and the
  // rebuilt TLAS into buffers made at init, keeping this frame's placement as the previous one
  // for object motion vectors. Call it every frame while anything moves. No Vulkan allocation.
  void setInstanceTransforms(std::span<const glm::mat4> objectToWorld);
  // The sun and sky from now on (a moving sun, day and night). A change that is no longer
  // motion (isLightingCut: the sun turned by more than settings().lightingCutDegrees, or its
  // or the sky's brightness changed by more than half) is a lighting cut: the GI system
  // rebuilds its light quickly (DiffuseGi::lightingCut) while the view's history stays.
  void setSunAndSky(const Sun& sun, const Sky& sky);

  // Declares, records, submits and waits for one frame seen from `camera`. Returns the GPU
  // time of each pass (debug-view copies included), in recording order.
  std::vector<vk::PassTiming> render(const Camera& camera);

  // A pass name shows the first image it writes; a resource name shows that image. Takes
  // effect from the next frame on (it creates a readback buffer).
  void requestDebugView(const std::string& passOrResource) {
    graph_.requestDebugView(passOrResource);
  }
  // The view as captured by the last frame (linear values; see graph/debug_view_image.h).
  ImageRGBA32F debugViewImage(const std::string& name) const;
  // Forgets temporal history (a camera cut).
  void resetHistory() {
    graph_.resetHistory();
    if (gi_) gi_->resetHistory();
  }
  // Facts about the last frame from the GI system (empty without one).
  std::vector<GiStatistic> giStatistics() const {
    return gi_ ? gi_->statistics() : std::vector<GiStatistic>{};
  }

  const HybridSettings& settings() const { return settings_; }
  const graph::FrameGraph& graph() const { return graph_; }

 private:
  struct Draw {
    uint32_t instance;
    uint32_t geometry;  // global
    uint32_t triangles;
  };
  // The draws whose instance box meets the camera's frustum, opaque ones first.
  void cullDraws(const glm::mat4& viewProjection);

  void recordFrame();
  gpu::FrameConstants makeFrameConstants(const Camera& camera) const;
  void drawVBuffer(VkCommandBuffer cmd, const graph::ResolvedImage& ids,
                   const graph::ResolvedImage& depth) const;
  gpu::HybridPassConstants passConstants(bool historyValid = false) const;

  vk::Context& context_;
  GpuScene& gpuScene_;
  HybridSettings settings_;
  Sun sun_;
  Sky sky_;
  LightingCutDetector lightingCuts_;
  // Set by setSunAndSky on a lighting cut, cleared after the next frame: that frame's shadow
  // denoiser starts afresh (its running mean would otherwise show the old shadows for up to
  // shadowMaxHistory frames).
  bool lightingCutPending_ = false;
  float nearPlane_ = 1e-3f;
  std::vector<Draw> opaqueDraws_, alphaTestedDraws_;  // every (instance, geometry) with triangles
  std::vector<Draw> visibleOpaque_, visibleAlphaTested_;  // this frame's, capacity reserved once
  vk::Buffer frameConstantsBuffer_;
  vk::Buffer punctualLights_, directionalLights_;
  uint32_t punctualLightCount_ = 0, directionalLightCount_ = 0;

  vk::GraphicsPipeline vbufferOpaque_, vbufferAlphaTest_;
  ImageComputePass vbufferTrace_, gbuffer_, shadowsTrace_, shadowsDenoise_, skyPass_, composite_, tonemap_;
  vk::GpuTimer timer_;
  std::unique_ptr<DiffuseGi> gi_;  // nullptr for --gi none
  graph::FrameGraph graph_;  // after what it imports: destroyed first

  gpu::FrameConstants constants_{};
  glm::mat4 previousViewProjection_{1.0f};
  bool hasPreviousFrame_ = false;
};

}  // namespace bounce
