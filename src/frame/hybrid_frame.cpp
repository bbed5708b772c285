#include "frame/hybrid_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "denoise/svgf.h"
#include "di/di_debug_views.h"
#include "gi/evolve/cache/clipmap_cache.h"
#include "gi/evolve/cache_gi.h"
#include "gi/evolve/restir/restir_gi.h"
#include "gi/gi10/gi10_gi.h"
#include "gi/lux/lux_gi.h"
#include "graph/debug_view_image.h"
#include "lighting/light_table.h"
#include "passes/primary_view.h"
#include "rt/scene_bvh.h"
#include "vk/memory_barrier.h"
#include "vk/pipeline_log.h"

namespace bounce {

namespace {

glm::mat4 fromRows(const glm::vec4& r0, const glm::vec4& r1, const glm::vec4& r2,
                   const glm::vec4& r3) {
  return glm::transpose(glm::mat4(r0, r1, r2, r3));
}

vk::Buffer uploadStorage(vk::Context& context, std::span<const std::byte> bytes,
                         const std::string& name) {
  return vk::uploadBuffer(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
}

// The diffuse GI system for `settings.gi`; nullptr for GiMode::None (gi.diffuse then stays
// zero).
std::unique_ptr<DiffuseGi> makeDiffuseGi(vk::Context& context, GpuScene& gpuScene,
                                         const Scene& scene, const HybridSettings& settings) {
  switch (settings.gi) {
    case GiMode::None:
      return nullptr;
    case GiMode::Evolve:
      return std::make_unique<RestirGi>(context, gpuScene, scene, settings.restirGi, settings.cache,
                                        settings.resolution());
    case GiMode::Cache:
      return std::make_unique<CacheGi>(context, gpuScene, scene, settings.cache);
    case GiMode::Lux:
      return std::make_unique<LuxGi>(context, gpuScene, scene, settings.lux, settings.restirGi,
                                     settings.cache, settings.resolution());
    case GiMode::Gi10:
      return std::make_unique<Gi10Gi>(context, gpuScene, scene, settings.gi10,
                                      settings.resolution());
  }
  return nullptr;
}

}  // namespace

// GpuCamera shoots dir = forward + x right - y up through NDC (x, y), with right and up scaled
// by the half-extents of the image plane at distance 1. Projecting a point d = p - position
// back: x = dot(d, right) / |right|^2 / dot(d, forward), likewise y with -up (Vulkan's clip y
// points down, as pixel rows do); w = view depth; z = near, so depth = near / view depth.
glm::mat4 viewProjection(const gpu::GpuCamera& camera, float nearPlane) {
  glm::vec3 r = camera.right / glm::dot(camera.right, camera.right);
  glm::vec3 u = -camera.up / glm::dot(camera.up, camera.up);
  glm::vec3 f = camera.forward;
  glm::vec3 p = camera.position;
  return fromRows({r, -glm::dot(r, p)}, {u, -glm::dot(u, p)}, {0.0f, 0.0f, 0.0f, nearPlane},
                  {f, -glm::dot(f, p)});
}

HybridFrame::HybridFrame(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                         const HybridSettings& settings)
    : context_(context),
      gpuScene_(gpuScene),
      scene_(scene),
      settings_(settings),
      sun_(scene.sun),
      sky_(scene.sky),
      lightingCuts_(scene.sun, scene.sky, settings.lightingCutDegrees),
      specularAlbedo_(context),
      sceneUpdate_(context, gpuScene),
      vbuffer_(context, gpuScene, scene, settings.vbuffer),
      gbuffer_(context, gpuScene),
      gbufferImport_(context, gpuScene),
      shadowsTrace_(context, gpuScene, settings.shadows),
      shadowsDenoise_(context, gpuScene),
      skyPass_(context, gpuScene),
      reflectionsTrace_(context, gpuScene, scene, specularAlbedo_, settings.reflections),
      reflectionsDenoise_(context, gpuScene, settings.reflectionDenoise),
      reflectionsUpsample_(context, gpuScene),
      composite_(context, gpuScene, specularAlbedo_),
      tonemap_(context, gpuScene),
      timer_(context) {
  validate(settings);
  // Reversed Z keeps float depth precise far away; the near plane only has to sit in front of
  // everything the camera should see.
  Aabb bounds = gpuScene.bounds();
  float radius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.extent());
  nearPlane_ = std::max(1e-4f, 1e-4f * radius);

  gi_ = makeDiffuseGi(context, gpuScene, scene, settings);
  if (settings.di.enabled()) {
    di_.emplace(context, gpuScene, scene, settings.di);
    // No light for DI: no DI pass runs and composite reads none (as with --di off, whose
    // unshadowed loop then has no light either).
    if (!di_->hasLights()) di_.reset();
  }
  if (settings.autoExposure) autoExposure_.emplace(context, gpuScene, settings.exposure);
  if (settings.taa.enabled) taa_.emplace(context, gpuScene, settings.taa);
  if (settings.reflections.reuseEnabled())
    reflectionsReuse_.emplace(context, gpuScene, specularAlbedo_, settings.reflections);
  if (settings.reflections.mirrorPassEnabled()) reflectionsTraceMirrors_.emplace(context, gpuScene);

  LightTable lights = buildLightTable(scene, gpuScene.bvh());
  punctualLightCount_ = uint32_t(lights.punctualLights.size());
  punctualLights_ = uploadStorage(context, std::as_bytes(std::span(lights.punctualLights)),
                                  "hybrid.punctual-lights");
  // The sun comes first in the distant-light table when it shines; it is lit with shadows
  // separately, the KHR directional lights after it are not.
  std::span<const gpu::GpuDistantLight> directional(lights.distantLights);
  if (sun_.irradiance > 0.0f && !directional.empty()) directional = directional.subspan(1);
  directionalLightCount_ = uint32_t(directional.size());
  directionalLights_ =
      uploadStorage(context, std::as_bytes(directional), "hybrid.directional-lights");
}

// `jitter`: the sub-pixel offset of the primary visibility (FrameConstants::jitter); both
// matrices are shifted by it, the previous one from its unjittered self (motion stays
// unjittered).
gpu::FrameConstants HybridFrame::makeFrameConstants(const Camera& camera, glm::vec2 jitter) const {
  gpu::FrameConstants c{};
  c.camera = makeGpuCamera(camera, settings_.width, settings_.height, gpuScene_.bounds());
  const glm::mat4 unjittered = viewProjection(c.camera, nearPlane_);
  const glm::uvec2 resolution{settings_.width, settings_.height};
  c.jitter = jitter;
  c.viewProjection = jitteredViewProjection(unjittered, jitter, resolution);
  c.previousViewProjection = jitteredViewProjection(
      hasPreviousFrame_ ? previousViewProjection_ : unjittered, jitter, resolution);
  c.towardSun = -glm::normalize(sun_.direction);
  c.sunCosHalfAngle = std::cos(glm::radians(0.5f * sun_.angularDiameterDegrees));
  c.sunIrradiance = sun_.irradiance * sun_.color;
  c.skyModel = sky_.model == SkyModel::Daylight ? gpu::FRAME_SKY_DAYLIGHT : gpu::FRAME_SKY_CONSTANT;
  c.skyRadiance = sky_.radiance;
  c.skyTurbidity = sky_.turbidity;
  c.skyScale = daylightSkyScale(sun_);
  c.skyAmbientStrength = settings_.skyAmbientStrength;
  c.exposure = std::exp2(settings_.exposureStops);
  c.frameIndex = uint32_t(graph_.frameIndex()) + settings_.noiseSeed;
  c.resolution = {settings_.width, settings_.height};
  c.shadowDivisor = settings_.shadows.divisor;
  const VkExtent2D shadowResolution = settings_.shadows.resolution(settings_.resolution());
  c.shadowResolution = {shadowResolution.width, shadowResolution.height};
  c.flags = settings_.lambert ? gpu::FRAME_FLAG_LAMBERT : 0u;
  c.punctualLights = punctualLights_.address();
  c.directionalLights = directionalLights_.address();
  c.punctualLightCount = punctualLightCount_;
  c.directionalLightCount = directionalLightCount_;
  c.shadowMaxHistory = settings_.shadows.maxHistory;
  c.nearPlane = nearPlane_;
  c.previousInstances = gpuScene_.previousInstanceBuffer().address();
  c.specularAlbedo = specularAlbedo_.address();
  return c;
}

void HybridFrame::setSunAndSky(const Sun& sun, const Sky& sky) {
  if (lightingCuts_.next(sun, sky)) {
    lightingCutPending_ = true;
    if (gi_) gi_->lightingCut();
  }
  sun_ = sun;
  sky_ = sky;
}

void HybridFrame::setInstanceTransforms(std::span<const glm::mat4> objectToWorld) {
  if (gpuScene_.setInstanceTransforms(objectToWorld)) sceneMoved_ = true;
  if (di_) di_->instancesMoved();
}

void HybridFrame::setLights(std::span<const PunctualLight> lights) {
  if (di_) di_->setLights(lights);
}

// The time since the last frame (0 for the first), from setTime() or the nominal frame time.
void HybridFrame::advanceTime() {
  const double now = nextTime_.value_or(time_.value_or(0.0) + kNominalFrameSeconds);
  deltaSeconds_ = time_ ? float(std::max(0.0, now - *time_)) : 0.0f;
  time_ = now;
  nextTime_.reset();
}

std::vector<vk::PassTiming> HybridFrame::render(const Camera& camera) {
  advanceTime();
  const glm::vec2 jitter = settings_.taa.enabled
                               ? taaJitter(graph_.frameIndex(), settings_.taa.jitterPhases)
                               : glm::vec2(0.0f);
  constants_ = makeFrameConstants(camera, jitter);
  if (sceneMoved_) constants_.flags |= gpu::FRAME_FLAG_SCENE_MOVED;
  sceneMoved_ = false;
  // Only a whole frame runs DI: renderGi's host lights its own frame, so there the GI keeps the
  // emission of every emitter.
  if (di_) constants_.flags |= gpu::FRAME_FLAG_DI_LIGHTS;
  recordFrame();
  return submitFrame();
}

std::vector<vk::PassTiming> HybridFrame::renderGi(const Camera& camera,
                                                  const HostGBufferImages& host) {
  if (!gi_) fail("bring your own G-buffer: the renderer has no GI system (gi none)");
  checkHostGBuffer(host, {settings_.width, settings_.height}, "bring your own G-buffer");
  advanceTime();
  constants_ = makeFrameConstants(camera, glm::vec2(0.0f));  // the host's camera: no jitter
  if (sceneMoved_) constants_.flags |= gpu::FRAME_FLAG_SCENE_MOVED;
  sceneMoved_ = false;
  recordGiFrame(host);
  return submitFrame(true);
}

// Bounce's frames wait for one another; a renderGi frame also follows the host's work on the
// queue in between (its G-buffer writes, its reads of the last gi.diffuse), which the graph does
// not see: one global barrier from everything before orders them (the host contract,
// include/bounce/host_gbuffer.h).
std::vector<vk::PassTiming> HybridFrame::submitFrame(bool afterHostWork) {
  graph_.allocate(context_, {settings_.width, settings_.height});  // a no-op after frame 0
  // BOUNCE_PIPELINE_TIMES: the first frame's passes one by one, to see what each one's first
  // dispatch costs (shader compilation on lavapipe; vk/pipeline_log.h).
  const bool firstFramePassByPass = !hasPreviousFrame_ && vk::pipelineTimesRequested();
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    if (afterHostWork) {
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    }
    timer_.reset(cmd);
    if (!firstFramePassByPass) graph_.execute(cmd, &timer_);
  });
  if (firstFramePassByPass) graph_.executePassByPass(&timer_);
  if (gi_) gi_->afterFrame();
  lightingCutPending_ = false;
  previousViewProjection_ = viewProjection(constants_.camera, nearPlane_);
  hasPreviousFrame_ = true;
  return timer_.available() ? timer_.read() : std::vector<vk::PassTiming>{};
}

void HybridFrame::countRays(bool on) {
  gpuScene_.setRayCounting(on);
  timer_.countRays(on ? gpuScene_.rayCounter().handle() : VK_NULL_HANDLE);
}

void HybridFrame::requestDebugView(const std::string& passOrResource) {
  if (di_ && passOrResource == kDiGridView) di_->showLightGrid(true);
  graph_.requestDebugView(di_ && isDiDerivedView(passOrResource) ? kDiInfoResource
                                                                 : passOrResource);
}

void HybridFrame::clearDebugViews() {
  graph_.clearDebugViews();
  if (di_) di_->showLightGrid(false);
}

ImageRGBA32F HybridFrame::debugViewImage(const std::string& name) const {
  if (di_ && isDiDerivedView(name))
    return diDerivedView(name, graph::debugViewImage(graph_.readDebugView(kDiInfoResource)));
  graph::DebugView view = graph_.readDebugView(name);
  if (isDiReservoirView(view)) return decodeDiReservoirView(view);
  if (isSvgfSurfaceView(view)) return decodeSvgfSurfaceView(view);
  return graph::debugViewImage(view);
}

void HybridFrame::resize(uint32_t width, uint32_t height) {
  HybridSettings resized = settings_;
  resized.width = width;
  resized.height = height;
  validate(resized);
  if (width == settings_.width && height == settings_.height) return;
  settings_ = resized;
  gi_.reset();  // its images and sizes follow the resolution
  gi_ = makeDiffuseGi(context_, gpuScene_, scene_, settings_);
  graph_.resetHistory();
  hasPreviousFrame_ = false;
}

std::vector<std::string> HybridFrame::passNames() {
  if (graph_.declaredPassNames().empty()) recordFrame();
  return graph_.declaredPassNames();
}

std::vector<std::string> HybridFrame::resourceNames() {
  if (graph_.declaredPassNames().empty()) recordFrame();
  std::vector<std::string> names = graph_.declaredResourceNames();
  if (di_)
    for (const std::string& name : diDerivedViewNames()) names.push_back(name);
  if (di_ && di_->usesLightGrid() &&
      std::find(names.begin(), names.end(), kDiGridView) == names.end())
    names.push_back(kDiGridView);
  return names;
}

// The frame, top to bottom (DESIGN.md §4): each pass declares its resources and accesses and
// hands its typed outputs to the next; the graph derives every barrier from the declarations.
void HybridFrame::recordFrame() {
  graph_.beginFrame();
  FrameContext frame = sceneUpdate_.declare(graph_, constants_, lightingCutPending_);
  VBuffer vbuffer = vbuffer_.declare(graph_, frame);
  GBuffer gbuffer = gbuffer_.declare(graph_, frame, vbuffer);
  RawShadows rawShadows = shadowsTrace_.declare(graph_, frame, gbuffer);
  Shadows shadows = shadowsDenoise_.declare(graph_, frame, gbuffer, rawShadows);
  DirectLightImage direct;
  direct.radiance =
      di_ ? di_->declare(graph_, frame, gbuffer).radiance
          : graph_.createPersistentImage("di.radiance", {VK_FORMAT_R16G16B16A16_SFLOAT});
  SkyImage sky = skyPass_.declare(graph_, frame, gbuffer);
  IndirectLight indirect;
  // Without a GI system composite reads zero diffuse light.
  indirect.diffuse =
      gi_ ? gi_->declare(graph_, {frame, gbuffer, shadows}).diffuse
          : graph_.createPersistentImage("gi.diffuse", {VK_FORMAT_R16G16B16A16_SFLOAT});
  declareReflections(frame, gbuffer, indirect);
  HdrImage hdr = composite_.declare(graph_, frame, gbuffer, shadows, direct, sky, indirect);
  std::optional<Exposure> exposure;
  if (autoExposure_)
    exposure = autoExposure_->declare(graph_, hdr, settings_.exposureStops, deltaSeconds_);
  // Exposure meters the composite; taa maps it (and its history) to a perceptual space with
  // this frame's exposure, and tonemap shows the anti-aliased image.
  if (taa_) hdr = taa_->declare(graph_, frame, gbuffer, hdr, exposure);
  tonemap_.declare(graph_, frame, hdr, exposure);
}

// reflections-trace (which looks the GI's radiance cache up at its hits when it has one), the
// reuse passes (reflections-temporal, -spatial, -resolve; unless ReflectionSettings::reuse is
// off), reflections-denoise-temporal and -spatial (unless turned off), reflections-upsample and
// reflections-trace-mirrors (curved mirrors' own rays at render resolution, unless turned off);
// without reflection rays (divisor 0) composite takes every surface's specular light from the
// diffuse GI and reads a zero `reflections`.
void HybridFrame::declareReflections(const FrameContext& frame, const GBuffer& gbuffer,
                                     IndirectLight& indirect) {
  if (!settings_.reflections.enabled()) {
    indirect.reflections =
        graph_.createPersistentImage("reflections", {VK_FORMAT_R16G16B16A16_SFLOAT});
    return;
  }
  RadianceCacheLookup cache;
  if (const ClipmapCache* clipmap = gi_ ? gi_->clipmapCache() : nullptr) {
    cache.constants = clipmap->constantsAddress();
    cache.declare = [clipmap](graph::PassBuilder pass) { return clipmap->declareLookup(pass); };
  }
  const gpu::ReflectionPassConstants constants =
      reflectionsTrace_.constants(frame, cache.constants);
  TracedReflections traced = reflectionsTrace_.declare(graph_, frame, gbuffer, cache);
  // ReSTIR-style reuse of the glossy samples: the resolved signal replaces the traced one.
  if (reflectionsReuse_) traced = reflectionsReuse_->declare(graph_, frame, gbuffer, traced);
  if (settings_.reflectionDenoise.enabled)
    traced = reflectionsDenoise_.declare(graph_, frame, gbuffer, traced, constants);
  const Reflections reflections =
      reflectionsUpsample_.declare(graph_, frame, gbuffer, traced, constants);
  if (reflectionsTraceMirrors_)
    reflectionsTraceMirrors_->declare(graph_, frame, gbuffer, cache, constants, traced,
                                      reflections);
  indirect.reflections = reflections.radiance;
  indirect.reflectionMaxRoughness = settings_.reflections.maxTracedRoughness;
}

// Bring your own G-buffer: the same chain up to the GI system, with the GBuffer imported from the
// host's images; `gi-output` hands gi.diffuse to the host (it has side effects, so the GI passes
// that write it are not culled although nothing in the frame reads it).
void HybridFrame::recordGiFrame(const HostGBufferImages& host) {
  graph_.beginFrame();
  FrameContext frame = sceneUpdate_.declare(graph_, constants_, lightingCutPending_);
  GBuffer gbuffer = gbufferImport_.declare(graph_, frame, host);
  RawShadows rawShadows = shadowsTrace_.declare(graph_, frame, gbuffer);
  Shadows shadows = shadowsDenoise_.declare(graph_, frame, gbuffer, rawShadows);
  DiffuseGiOutput gi = gi_->declare(graph_, {frame, gbuffer, shadows});
  graph_.addPass("gi-output", graph::QueueKind::Compute)
      .read(gi.diffuse, graph::Access::StorageRead)
      .sideEffects();
}

}  // namespace bounce
