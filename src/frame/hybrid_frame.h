// The hybrid frame (DESIGN.md §4; seed 000's hybrid renderer): scene-update, vbuffer, gbuffer,
// shadows-trace, shadows-denoise, ReSTIR DI (di-*), sky, the diffuse GI system, composite,
// automatic exposure (exposure-histogram, exposure-adapt), taa (when on), tonemap; each a pass unit
// of src/passes/ (or src/gi/) declared on the frame graph once per frame by recordFrame(), a
// straight chain in which each pass takes the typed outputs of the ones before. Resources are
// created by the first frame (and a resize); later frames only update the frame constants and
// record.
//
//   HybridFrame frame(context, gpuScene, scene, settings);
//   frame.requestDebugView("composite");      // any pass or resource by name
//   for (...) frame.render(camera);           // submits and waits; returns per-pass timings
//   ImageRGBA32F hdr = frame.debugViewImage("composite");
//
// Bring your own G-buffer: renderGi(camera, hostImages) runs `gbuffer-import` on the host's
// images instead of vbuffer + gbuffer and stops at gi.diffuse (giImage()).
#pragma once
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <memory>
#include <optional>

#include "di/restir_di.h"
#include "frame/frame_settings.h"
#include "frame/lighting_cut.h"
#include "gi/diffuse_gi.h"
#include "graph/frame_graph.h"
#include "lighting/specular_albedo.h"
#include "passes/auto_exposure.h"
#include "passes/composite.h"
#include "passes/gbuffer.h"
#include "passes/gbuffer_import.h"
#include "passes/reflections_denoise.h"
#include "passes/reflections_reuse.h"
#include "passes/reflections_trace.h"
#include "passes/reflections_trace_mirrors.h"
#include "passes/reflections_upsample.h"
#include "passes/scene_update.h"
#include "passes/shadows_denoise.h"
#include "passes/shadows_trace.h"
#include "passes/sky.h"
#include "passes/taa.h"
#include "passes/tonemap.h"
#include "passes/vbuffer.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "shared/hybrid_frame_io.h"
#include "tools/image_io.h"
#include "vk/gpu_timer.h"

namespace bounce {

// World to Vulkan clip space for the camera that shoots rays through pixel centres
// (shared/camera.h): y down, reversed Z with an infinite far plane, depth = near / view depth.
glm::mat4 viewProjection(const gpu::GpuCamera& camera, float nearPlane);

class HybridFrame {
 public:
  // `scene` must be the one `gpuScene` was built from.
  HybridFrame(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
              const HybridSettings& settings);

  // Time-varying scene state for the next render() (scene/animation.h evaluates it).
  // Instances: one objectToWorld per scene instance; `scene-update` uploads them and the
  // rebuilt TLAS into buffers made at init, keeping this frame's placement as the previous one
  // for object motion vectors. Call it every frame while anything moves. No Vulkan allocation.
  void setInstanceTransforms(std::span<const glm::mat4> objectToWorld);
  // The pose of the deforming meshes (skins, morph targets) for the next render(); scene-update
  // poses them on the GPU and refits their BLAS (rt/gpu_deformer.h). Call it every frame while
  // they move. No Vulkan allocation. Emissive triangles of deforming meshes keep their rest
  // pose in ReSTIR DI's light tables (docs/di.md).
  void setDeformation(const DeformationPose& pose) {
    gpuScene_.setDeformation(pose);
    sceneMoved_ = true;
  }
  // The scene's KHR punctual lights from the next render() on (Scene::lights, the same count
  // and types, with positions, directions, colours and intensities animated; intensity 0 is
  // off). ReSTIR DI's light tables follow in place (RestirDi::setLights), as do its emissive
  // triangles with setInstanceTransforms; the GI's own light tables keep the scene's lights
  // (docs/di.md, "Light animation"). No Vulkan allocation.
  void setLights(std::span<const PunctualLight> lights);
  // The compute pipelines ReSTIR DI compiles (0 with --di off).
  uint32_t diPipelineCount() const { return di_ ? di_->pipelineCount() : 0; }
  // The sun and sky from now on (a moving sun, day and night). A change that is no longer
  // motion (isLightingCut: the sun turned by more than settings().lightingCutDegrees, or its
  // or the sky's brightness changed by more than half) is a lighting cut: the GI system
  // rebuilds its light quickly (DiffuseGi::lightingCut) while the view's history stays.
  void setSunAndSky(const Sun& sun, const Sky& sky);
  // The time of the next render() in seconds (animation time, never decreasing): what
  // automatic exposure adapts over. A frame without it comes kNominalFrameSeconds after the
  // last.
  void setTime(double seconds) { nextTime_ = seconds; }
  static constexpr double kNominalFrameSeconds = 1.0 / 60.0;

  // Declares, records, submits and waits for one frame seen from `camera`. Returns the GPU
  // time of each pass (debug-view copies included), in recording order.
  std::vector<vk::PassTiming> render(const Camera& camera);
  // From the next frame on, each PassTiming also has the rays its pass traced (every
  // traceClosest/traceVisibility call, counted on the GPU: GpuScene::setRayCounting). Waits
  // for the device. Counting adds a barrier after each pass; bench times with it on unless
  // told otherwise (docs/benchmarks.md gives the cost).
  void countRays(bool on);

  // Bring your own G-buffer (issue 17): one frame seen from `camera` whose GBuffer comes from
  // the host's images (`gbuffer-import` instead of vbuffer + gbuffer) and that ends at the GI
  // system's gi.diffuse (no sky, composite or tonemap). `camera` must be the one the host
  // rendered with. Submits and waits; returns the pass timings like render(). The frame's
  // gi.diffuse is then giImage(). Needs a GI mode (settings().gi != None).
  std::vector<vk::PassTiming> renderGi(const Camera& camera, const HostGBufferImages& host);
  // After renderGi(): gi.diffuse as that frame left it (image, view, format, extent, layout),
  // valid until the next frame.
  graph::ResolvedImage giImage() const { return graph_.resolvedImage("gi.diffuse"); }

  // A pass name shows the first image it writes; a resource name shows that image. Takes
  // effect from the next frame on (it creates a readback buffer).
  // DI's derived views (di.light, di.m, di.w, di.visibility: di/di_debug_views.h) request
  // di.reservoir-info.
  void requestDebugView(const std::string& passOrResource);
  void clearDebugViews();
  // The view as captured by the last frame (linear values; see graph/debug_view_image.h; DI's
  // reservoirs decoded and its derived views computed, di/di_debug_views.h).
  ImageRGBA32F debugViewImage(const std::string& name) const;
  // Forgets temporal history (a camera cut).
  // Automatic exposure takes the next frame's metered exposure directly.
  void resetHistory() {
    graph_.resetHistory();
    if (gi_) gi_->resetHistory();
  }
  // Facts about the last frame from the GI system (empty without one).
  std::vector<GiStatistic> giStatistics() const {
    return gi_ ? gi_->statistics() : std::vector<GiStatistic>{};
  }

  // A new render resolution from the next frame on: every resolution-dependent size (shadow and
  // GI images) follows from settings, the GI system is rebuilt and history is reset.
  void resize(uint32_t width, uint32_t height);

  // The passes and resources a frame of these settings declares (declaring one first if none
  // was): the names requestDebugView() accepts, as the graph knows them (resources: with DI's
  // derived views).
  std::vector<std::string> passNames();
  std::vector<std::string> resourceNames();

  const HybridSettings& settings() const { return settings_; }
  const graph::FrameGraph& graph() const { return graph_; }

 private:
  void recordFrame();
  void declareReflections(const FrameContext& frame, const GBuffer& gbuffer,
                          IndirectLight& indirect);
  void recordGiFrame(const HostGBufferImages& host);
  std::vector<vk::PassTiming> submitFrame(bool afterHostWork = false);
  gpu::FrameConstants makeFrameConstants(const Camera& camera, glm::vec2 jitter) const;
  void advanceTime();

  vk::Context& context_;
  GpuScene& gpuScene_;
  const Scene& scene_;
  HybridSettings settings_;
  Sun sun_;
  Sky sky_;
  LightingCutDetector lightingCuts_;
  // Set by setSunAndSky on a lighting cut, cleared after the next frame.
  bool lightingCutPending_ = false;
  // Whether the next frame's instances or deforming meshes differ from the last frame's
  // (gpu::FRAME_FLAG_SCENE_MOVED).
  bool sceneMoved_ = false;
  float nearPlane_ = 1e-3f;
  vk::Buffer punctualLights_, directionalLights_;
  uint32_t punctualLightCount_ = 0, directionalLightCount_ = 0;

  SpecularAlbedoTable specularAlbedo_;  // before the passes that read it
  SceneUpdatePass sceneUpdate_;
  VBufferPass vbuffer_;
  GBufferPass gbuffer_;
  GBufferImportPass gbufferImport_;
  ShadowsTracePass shadowsTrace_;
  ShadowsDenoisePass shadowsDenoise_;
  SkyPass skyPass_;
  ReflectionsTracePass reflectionsTrace_;
  std::optional<ReflectionsReuse> reflectionsReuse_;  // settings.reflections.reuseEnabled()
  ReflectionsDenoisePass reflectionsDenoise_;
  ReflectionsUpsamplePass reflectionsUpsample_;
  // settings.reflections.mirrorPassEnabled()
  std::optional<ReflectionsTraceMirrorsPass> reflectionsTraceMirrors_;
  CompositePass composite_;
  std::optional<AutoExposure> autoExposure_;  // settings.autoExposure
  std::optional<TaaPass> taa_;                // settings.taa.enabled
  TonemapPass tonemap_;
  vk::GpuTimer timer_;
  std::unique_ptr<DiffuseGi> gi_;  // nullptr for --gi none
  std::optional<RestirDi> di_;     // DiSettings::enabled() and RestirDi::hasLights()
  graph::FrameGraph graph_;        // after what it imports: destroyed first

  gpu::FrameConstants constants_{};
  glm::mat4 previousViewProjection_{1.0f};  // unjittered
  bool hasPreviousFrame_ = false;
  std::optional<double> nextTime_;  // setTime()
  std::optional<double> time_;      // of the last frame rendered
  float deltaSeconds_ = 0.0f;       // this frame's time since the last
};

}  // namespace bounce
