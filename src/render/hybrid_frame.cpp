#include "render/hybrid_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "graph/debug_view_image.h"
#include "lighting/light_table.h"
#include "passes/primary_view.h"
#include "rt/scene_bvh.h"

namespace bounce {

namespace {

using graph::Access;
using graph::QueueKind;

constexpr VkFormat kIdsFormat = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kZBufferFormat = VK_FORMAT_D32_SFLOAT;

glm::mat4 fromRows(const glm::vec4& r0, const glm::vec4& r1, const glm::vec4& r2,
                   const glm::vec4& r3) {
  return glm::transpose(glm::mat4(r0, r1, r2, r3));
}

vk::Buffer uploadOrPlaceholder(vk::Context& context, std::span<const std::byte> bytes,
                               const std::string& name) {
  return vk::uploadBuffer(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
}

vk::GraphicsPipelineDesc vbufferPipeline(const GpuScene& gpuScene, const char* fragmentShader) {
  return {.vertexShader = "passes/vbuffer.vert",
          .fragmentShader = fragmentShader,
          .setLayouts = {&gpuScene.setLayout()},
          .pushConstantBytes = sizeof(gpu::VBufferDrawConstants),
          .colorFormats = {kIdsFormat},
          .depthFormat = kZBufferFormat};
}

bool alphaTested(const Scene& scene, uint32_t material) {
  return material < scene.materials.size() &&
         scene.materials[material].alphaMode != AlphaMode::Opaque;
}

// Whether the box is entirely outside one of the frustum's planes, the planes taken from the
// clip-space conditions -w <= x <= w, -w <= y <= w, z <= w (Gribb and Hartmann 2001); with
// reversed Z and an infinite far plane there is no far plane to test.
bool outsideFrustum(const glm::mat4& viewProjection, const Aabb& box) {
  const glm::mat4 rows = glm::transpose(viewProjection);
  const glm::vec4 planes[5] = {rows[3] + rows[0], rows[3] - rows[0], rows[3] + rows[1],
                               rows[3] - rows[1], rows[3] - rows[2]};
  for (const glm::vec4& plane : planes) {
    // The box corner furthest along the plane's normal.
    glm::vec3 corner(plane.x >= 0.0f ? box.max.x : box.min.x,
                     plane.y >= 0.0f ? box.max.y : box.min.y,
                     plane.z >= 0.0f ? box.max.z : box.min.z);
    if (glm::dot(glm::vec3(plane), corner) + plane.w < 0.0f) return true;
  }
  return false;
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
      settings_(settings),
      sun_(scene.sun),
      sky_(scene.sky),
      lightingCuts_(scene.sun, scene.sky, settings.lightingCutDegrees),
      frameConstantsBuffer_(context, sizeof(gpu::FrameConstants),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            vk::MemoryUse::DeviceOnly, "frame-constants"),
      vbufferOpaque_(context, vbufferPipeline(gpuScene, "passes/vbuffer_opaque.frag")),
      vbufferAlphaTest_(context, vbufferPipeline(gpuScene, "passes/vbuffer_alpha_test.frag")),
      vbufferTrace_(context, gpuScene, "passes/vbuffer_trace", 1),
      gbuffer_(context, gpuScene, "passes/gbuffer", 8),
      shadowsTrace_(context, gpuScene, "passes/shadows_trace", 4),
      shadowsDenoise_(context, gpuScene, "passes/shadows_denoise", 8),
      skyPass_(context, gpuScene, "passes/sky", 2),
      composite_(context, gpuScene, "passes/composite", 10),
      tonemap_(context, gpuScene, "passes/tonemap", 2),
      timer_(context) {
  if (settings.width == 0 || settings.height == 0 || settings.shadowDivisor == 0)
    fail("hybrid frame: resolution {}x{} and shadow divisor {} must be positive", settings.width,
         settings.height, settings.shadowDivisor);
  const rt::SceneBvh& bvh = gpuScene.bvh();
  for (uint32_t i = 0; i < bvh.instances.size(); ++i) {
    const gpu::GpuInstance& instance = bvh.instances[i];
    uint32_t geometryCount = uint32_t(scene.meshes[instance.mesh].geometries.size());
    for (uint32_t g = instance.geometryBase; g < instance.geometryBase + geometryCount; ++g)
      if (bvh.geometries[g].triangleCount > 0)
        (alphaTested(scene, bvh.geometries[g].material) ? alphaTestedDraws_ : opaqueDraws_)
            .push_back({i, g, bvh.geometries[g].triangleCount});
  visibleOpaque_.reserve(opaqueDraws_.size());
  visibleAlphaTested_.reserve(alphaTestedDraws_.size());
  }
  // Reversed Z keeps float depth precise far away; the near plane only has to sit in front of
  // everything the camera should see.
  Aabb bounds = gpuScene.bounds();
  float radius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.extent());
  nearPlane_ = std::max(1e-4f, 1e-4f * radius);

  gi_ = makeDiffuseGi(context, gpuScene, scene, settings);

  LightTable lights = buildLightTable(scene, bvh);
  punctualLightCount_ = uint32_t(lights.punctualLights.size());
  punctualLights_ = uploadOrPlaceholder(context, std::as_bytes(std::span(lights.punctualLights)),
                                        "hybrid.punctual-lights");
  // The sun comes first in the distant-light table when it shines; it is lit with shadows
  // separately, the KHR directional lights after it are not.
  std::span<const gpu::GpuDistantLight> directional(lights.distantLights);
  if (sun_.irradiance > 0.0f && !directional.empty()) directional = directional.subspan(1);
  directionalLightCount_ = uint32_t(directional.size());
  directionalLights_ =
      uploadOrPlaceholder(context, std::as_bytes(directional), "hybrid.directional-lights");
}

gpu::FrameConstants HybridFrame::makeFrameConstants(const Camera& camera) const {
  gpu::FrameConstants c{};
  c.camera = makeGpuCamera(camera, settings_.width, settings_.height, gpuScene_.bounds());
  c.viewProjection = viewProjection(c.camera, nearPlane_);
  c.previousViewProjection = hasPreviousFrame_ ? previousViewProjection_ : c.viewProjection;
  c.towardSun = -glm::normalize(sun_.direction);
  c.sunCosHalfAngle = std::cos(glm::radians(0.5f * sun_.angularDiameterDegrees));
  c.sunIrradiance = sun_.irradiance * sun_.color;
  c.skyModel = sky_.model == SkyModel::Daylight ? gpu::FRAME_SKY_DAYLIGHT : gpu::FRAME_SKY_CONSTANT;
  c.skyRadiance = sky_.radiance;
  c.skyTurbidity = sky_.turbidity;
  c.skyScale = daylightSkyScale(sun_);
  c.skyAmbientStrength = settings_.skyAmbientStrength;
  c.exposure = settings_.exposure;
  c.frameIndex = uint32_t(graph_.frameIndex());
  c.resolution = {settings_.width, settings_.height};
  c.shadowDivisor = settings_.shadowDivisor;
  c.shadowResolution = {(settings_.width + c.shadowDivisor - 1) / c.shadowDivisor,
                        (settings_.height + c.shadowDivisor - 1) / c.shadowDivisor};
  c.flags = settings_.lambert ? gpu::FRAME_FLAG_LAMBERT : 0u;
  c.punctualLights = punctualLights_.address();
  c.directionalLights = directionalLights_.address();
  c.punctualLightCount = punctualLightCount_;
  c.directionalLightCount = directionalLightCount_;
  c.shadowMaxHistory = settings_.shadowMaxHistory;
  c.nearPlane = nearPlane_;
  c.previousInstances = gpuScene_.previousInstanceBuffer().address();
  return c;
}

gpu::HybridPassConstants HybridFrame::passConstants(bool historyValid) const {
  return {frameConstantsBuffer_.address(), historyValid ? 1u : 0u, 0u};
}

namespace {
float skyBrightness(const Sky& sky) { return sky.radiance.x + sky.radiance.y + sky.radiance.z; }
}  // namespace

LightingCutDetector::LightingCutDetector(const Sun& sun, const Sky& sky, float cutDegrees)
    : sun_(sun),
      sky_(sky),
      cutDegrees_(cutDegrees),
      brightestSun_(sun.irradiance),
      brightestSky_(skyBrightness(sky)) {}

bool LightingCutDetector::next(const Sun& sun, const Sky& sky) {
  brightestSun_ = std::max(brightestSun_, sun.irradiance);
  brightestSky_ = std::max(brightestSky_, skyBrightness(sky));
  const bool lit = sun_.irradiance > 0.0f && sun.irradiance > 0.0f;
  const float cosine = glm::dot(glm::normalize(sun_.direction), glm::normalize(sun.direction));
  const bool turned = lit && cosine < std::cos(glm::radians(cutDegrees_)) - 1e-6f;
  const bool sunJumped = std::abs(sun.irradiance - sun_.irradiance) > 0.5f * brightestSun_;
  const bool skyJumped =
      std::abs(skyBrightness(sky) - skyBrightness(sky_)) > 0.5f * brightestSky_;
  const bool cut = cutDegrees_ >= 0.0f &&
                   (turned || sunJumped || skyJumped || sky.model != sky_.model);
  sun_ = sun;
  sky_ = sky;
  return cut;
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
  gpuScene_.setInstanceTransforms(objectToWorld);
}

std::vector<vk::PassTiming> HybridFrame::render(const Camera& camera) {
  constants_ = makeFrameConstants(camera);
  if (settings_.vbuffer == VBufferMode::Raster) cullDraws(constants_.viewProjection);
  recordFrame();
  graph_.allocate(context_, {settings_.width, settings_.height});  // a no-op after frame 0
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    timer_.reset(cmd);
    graph_.execute(cmd, &timer_);
  });
  if (gi_) gi_->afterFrame();
  lightingCutPending_ = false;
  previousViewProjection_ = constants_.viewProjection;
  hasPreviousFrame_ = true;
  return timer_.available() ? timer_.read() : std::vector<vk::PassTiming>{};
}

ImageRGBA32F HybridFrame::debugViewImage(const std::string& name) const {
  return graph::debugViewImage(graph_.readDebugView(name));
}

void HybridFrame::drawVBuffer(VkCommandBuffer cmd, const graph::ResolvedImage& ids,
                              const graph::ResolvedImage& depth) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = ids.view;
  color.imageLayout = ids.layout;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color.uint32[0] = gpu::VBUFFER_NO_HIT;
  VkRenderingAttachmentInfo zbuffer{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  zbuffer.imageView = depth.view;
  zbuffer.imageLayout = depth.layout;
  zbuffer.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  zbuffer.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  zbuffer.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, ids.extent};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  info.pDepthAttachment = &zbuffer;
  vkCmdBeginRendering(cmd, &info);
  for (const auto& [pipeline, draws] : {std::pair{&vbufferOpaque_, &visibleOpaque_},
                                        std::pair{&vbufferAlphaTest_, &visibleAlphaTested_}}) {
    if (draws->empty()) continue;
    pipeline->bind(cmd, {gpuScene_.descriptorSet()}, ids.extent);
    for (const Draw& d : *draws) {
      pipeline->push(cmd, gpu::VBufferDrawConstants{frameConstantsBuffer_.address(), d.instance,
                                                    d.geometry});
      vkCmdDraw(cmd, 3 * d.triangles, 1, 0, 0);
    }
  }
  vkCmdEndRendering(cmd);
}

void HybridFrame::cullDraws(const glm::mat4& viewProjection) {
  const rt::SceneBvh& bvh = gpuScene_.bvh();
  for (auto [all, visible] : {std::pair{&opaqueDraws_, &visibleOpaque_},
                              std::pair{&alphaTestedDraws_, &visibleAlphaTested_}}) {
    visible->clear();  // keeps the capacity: no allocation per frame
    for (const Draw& d : *all) {
      const gpu::GpuInstance& instance = bvh.instances[d.instance];
      if (!outsideFrustum(viewProjection,
                          rt::instanceWorldBounds(instance, bvh.meshBounds[instance.mesh])))
        visible->push_back(d);
    }
  }
}

// The frame, top to bottom (DESIGN.md §4 without GI). Resources first, then the passes in the
// order they run; the graph derives every barrier from the declared accesses.
void HybridFrame::recordFrame() {
  using graph::ImageSize;
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph_.beginFrame();
  graph::BufferHandle frame =
      graph_.importBuffer("frame-constants", graph::ImportedBuffer::from(frameConstantsBuffer_));
  // The scene arrays that move (GpuScene::setInstanceTransforms); declared so that the graph
  // orders this frame's upload after last frame's readers and before this frame's.
  graph::BufferHandle instances = graph_.importBuffer(
      "scene.instances", graph::ImportedBuffer::from(gpuScene_.instanceBuffer()));
  graph::BufferHandle previousInstances = graph_.importBuffer(
      "scene.previous-instances", graph::ImportedBuffer::from(gpuScene_.previousInstanceBuffer()));
  graph::BufferHandle tlas =
      graph_.importBuffer("scene.tlas-nodes", graph::ImportedBuffer::from(gpuScene_.tlasBuffer()));
  graph::ImageHandle ids = graph_.createImage("vbuffer.ids", {kIdsFormat});
  graph::ImageHandle baseColor = graph_.createImage("gbuffer.base-color", {rgba16f});
  graph::ImageHandle normals = graph_.createImage("gbuffer.normals", {rgba16f});
  graph::HistoryImage depth = graph_.createHistoryImage("gbuffer.depth", {VK_FORMAT_R32_SFLOAT});
  graph::ImageHandle uv = graph_.createImage("gbuffer.uv", {VK_FORMAT_R32G32_SFLOAT});
  graph::ImageHandle velocity = graph_.createImage("gbuffer.velocity", {VK_FORMAT_R16G16_SFLOAT});
  graph::ImageHandle emissive = graph_.createImage("gbuffer.emissive", {rgba16f});
  graph::ImageHandle flags = graph_.createImage("gbuffer.flags", {VK_FORMAT_R32_UINT});
  graph::ImageHandle shadowsRaw = graph_.createImage(
      "shadows.raw", {VK_FORMAT_R16_SFLOAT, ImageSize::dividedRes(settings_.shadowDivisor)});
  graph::HistoryImage shadows =
      graph_.createHistoryImage("shadows.visibility", {VK_FORMAT_R16G16_SFLOAT});
  graph::ImageHandle sky = graph_.createImage("sky.radiance", {rgba16f});
  // Input slots of the GI and reflection systems: the GI system (src/gi/diffuse_gi.h) writes
  // gi.diffuse; without one, and for reflections (nothing writes them yet), they stay zero.
  graph::ImageHandle giDiffuse = gi_ ? graph_.createImage("gi.diffuse", {rgba16f})
                                     : graph_.createPersistentImage("gi.diffuse", {rgba16f});
  graph::ImageHandle reflections = graph_.createPersistentImage("reflections", {rgba16f});
  graph::ImageHandle hdr = graph_.createImage("composite.hdr", {rgba16f});
  graph::ImageHandle display = graph_.createImage("tonemap.display", {rgba16f});
  VkExtent2D full{settings_.width, settings_.height};
  VkExtent2D shadowExtent{constants_.shadowResolution.x, constants_.shadowResolution.y};

  graph_.addPass("scene-update", QueueKind::Compute)
      .write(frame, Access::TransferDst)
      .write(instances, Access::TransferDst)
      .write(previousInstances, Access::TransferDst)
      .write(tlas, Access::TransferDst)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        vkCmdUpdateBuffer(cmd, r.buffer(frame).buffer, 0, sizeof(constants_), &constants_);
        gpuScene_.recordInstanceUpload(cmd);  // nothing when no instance moved
      });
  if (settings_.vbuffer == VBufferMode::Raster) {
    graph::ImageHandle zbuffer = graph_.createImage("vbuffer.depth", {kZBufferFormat});
    graph_.addPass("vbuffer", QueueKind::Graphics)
        .read(frame, Access::StorageRead)
        .read(instances, Access::StorageRead)
        .write(ids, Access::ColorAttachmentWrite)
        .write(zbuffer, Access::DepthAttachmentWrite)
        .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
          drawVBuffer(cmd, r.image(ids), r.image(zbuffer));
        });
  } else {
    graph_.addPass("vbuffer", QueueKind::Compute)
        .read(frame, Access::StorageRead)
        .read(instances, Access::StorageRead)
        .read(tlas, Access::StorageRead)
        .write(ids, Access::StorageWrite)
        .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
          vbufferTrace_.record(cmd, {{gpu::VBUFFER_TRACE_BINDING_IDS, r.image(ids)}},
                               passConstants(), full);
        });
  }
  graph_.addPass("gbuffer", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(instances, Access::StorageRead)
      .read(previousInstances, Access::StorageRead)
      .read(ids, Access::StorageRead)
      .write(baseColor, Access::StorageWrite)
      .write(normals, Access::StorageWrite)
      .write(depth.current, Access::StorageWrite)
      .write(uv, Access::StorageWrite)
      .write(velocity, Access::StorageWrite)
      .write(emissive, Access::StorageWrite)
      .write(flags, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        gbuffer_.record(cmd,
                        {{gpu::GBUFFER_BINDING_IDS, r.image(ids)},
                         {gpu::GBUFFER_BINDING_BASE_COLOR, r.image(baseColor)},
                         {gpu::GBUFFER_BINDING_NORMALS, r.image(normals)},
                         {gpu::GBUFFER_BINDING_DEPTH, r.image(depth.current)},
                         {gpu::GBUFFER_BINDING_UV, r.image(uv)},
                         {gpu::GBUFFER_BINDING_VELOCITY, r.image(velocity)},
                         {gpu::GBUFFER_BINDING_EMISSIVE, r.image(emissive)},
                         {gpu::GBUFFER_BINDING_FLAGS, r.image(flags)}},
                        passConstants(), full);
      });
  graph_.addPass("shadows-trace", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(instances, Access::StorageRead)
      .read(tlas, Access::StorageRead)
      .read(normals, Access::StorageRead)
      .read(depth.current, Access::StorageRead)
      .read(flags, Access::StorageRead)
      .write(shadowsRaw, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        shadowsTrace_.record(cmd,
                             {{gpu::SHADOWS_TRACE_BINDING_NORMALS, r.image(normals)},
                              {gpu::SHADOWS_TRACE_BINDING_DEPTH, r.image(depth.current)},
                              {gpu::SHADOWS_TRACE_BINDING_FLAGS, r.image(flags)},
                              {gpu::SHADOWS_TRACE_BINDING_RAW, r.image(shadowsRaw)}},
                             passConstants(), shadowExtent);
      });
  graph_.addPass("shadows-denoise", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(shadowsRaw, Access::StorageRead)
      .read(normals, Access::StorageRead)
      .read(depth.current, Access::StorageRead)
      .read(depth.previous, Access::StorageRead)
      .read(flags, Access::StorageRead)
      .read(velocity, Access::StorageRead)
      .read(shadows.previous, Access::StorageRead)
      .write(shadows.current, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        bool valid = r.historyValid(shadows) && r.historyValid(depth) && !lightingCutPending_;
        shadowsDenoise_.record(
            cmd,
            {{gpu::SHADOWS_DENOISE_BINDING_RAW, r.image(shadowsRaw)},
             {gpu::SHADOWS_DENOISE_BINDING_NORMALS, r.image(normals)},
             {gpu::SHADOWS_DENOISE_BINDING_DEPTH, r.image(depth.current)},
             {gpu::SHADOWS_DENOISE_BINDING_FLAGS, r.image(flags)},
             {gpu::SHADOWS_DENOISE_BINDING_VELOCITY, r.image(velocity)},
             {gpu::SHADOWS_DENOISE_BINDING_PREVIOUS_DEPTH, r.image(depth.previous)},
             {gpu::SHADOWS_DENOISE_BINDING_PREVIOUS, r.image(shadows.previous)},
             {gpu::SHADOWS_DENOISE_BINDING_CURRENT, r.image(shadows.current)}},
            passConstants(valid), full);
      });
  graph_.addPass("sky", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(flags, Access::StorageRead)
      .write(sky, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        skyPass_.record(
            cmd,
            {{gpu::SKY_BINDING_FLAGS, r.image(flags)}, {gpu::SKY_BINDING_RADIANCE, r.image(sky)}},
            passConstants(), full);
      });
  if (gi_) {
    FrameInputs inputs;
    inputs.frameConstants = frame;
    inputs.frameConstantsAddress = frameConstantsBuffer_.address();
    inputs.constants = &constants_;
    inputs.instances = instances;
    inputs.previousInstances = previousInstances;
    inputs.tlas = tlas;
    inputs.baseColor = baseColor;
    inputs.normals = normals;
    inputs.depth = depth;
    inputs.uv = uv;
    inputs.velocity = velocity;
    inputs.emissive = emissive;
    inputs.flags = flags;
    inputs.sunVisibility = shadows.current;
    inputs.resolution = full;
    gi_->declare(graph_, inputs, giDiffuse);
  }
  graph_.addPass("composite", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(baseColor, Access::StorageRead)
      .read(normals, Access::StorageRead)
      .read(depth.current, Access::StorageRead)
      .read(emissive, Access::StorageRead)
      .read(flags, Access::StorageRead)
      .read(shadows.current, Access::StorageRead)
      .read(sky, Access::StorageRead)
      .read(giDiffuse, Access::StorageRead)
      .read(reflections, Access::StorageRead)
      .write(hdr, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        composite_.record(cmd,
                          {{gpu::COMPOSITE_BINDING_BASE_COLOR, r.image(baseColor)},
                           {gpu::COMPOSITE_BINDING_NORMALS, r.image(normals)},
                           {gpu::COMPOSITE_BINDING_DEPTH, r.image(depth.current)},
                           {gpu::COMPOSITE_BINDING_EMISSIVE, r.image(emissive)},
                           {gpu::COMPOSITE_BINDING_FLAGS, r.image(flags)},
                           {gpu::COMPOSITE_BINDING_SHADOWS, r.image(shadows.current)},
                           {gpu::COMPOSITE_BINDING_SKY, r.image(sky)},
                           {gpu::COMPOSITE_BINDING_GI_DIFFUSE, r.image(giDiffuse)},
                           {gpu::COMPOSITE_BINDING_REFLECTIONS, r.image(reflections)},
                           {gpu::COMPOSITE_BINDING_OUTPUT, r.image(hdr)}},
                          passConstants(), full);
      });
  // The display image leaves the frame (a file, later a swapchain): kept even when no pass
  // reads it.
  graph_.addPass("tonemap", QueueKind::Compute)
      .read(frame, Access::StorageRead)
      .read(hdr, Access::StorageRead)
      .write(display, Access::StorageWrite)
      .sideEffects()
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        tonemap_.record(cmd,
                        {{gpu::TONEMAP_BINDING_HDR, r.image(hdr)},
                         {gpu::TONEMAP_BINDING_DISPLAY, r.image(display)}},
                        passConstants(), full);
      });
}

}  // namespace bounce
