#include <bounce/renderer.h>

#include <bounce/external_device.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "api/convert.h"
#include "api/scene_impl.h"
#include "core/error.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "rt/gpu_scene.h"
#include "vk/context.h"

namespace bounce::api {

namespace {

constexpr const char* kDisplayImage = "tonemap";

// Images only the full frame has: not captured by renderGi frames.
bool onlyInFullFrame(const std::string& name) {
  return name == "tonemap" || name == "composite" || name == "sky" || name == "sky.radiance" ||
         name == "tonemap.display" || name == "composite.hdr" || name == "vbuffer" ||
         name == "vbuffer.ids" || name == "vbuffer.depth" || name == "gbuffer";
}

graph::ImportedImage toImported(const HostImage& image) {
  graph::ImportedImage out;
  out.image = image.image;
  out.view = image.view;
  out.format = image.format;
  out.extent = {image.width, image.height};
  out.layout = VK_IMAGE_LAYOUT_GENERAL;
  return out;
}

}  // namespace

struct Renderer::Impl {
  // Uploads the scene and creates the frame on `context`.
  Impl(std::unique_ptr<vk::Context> context, const bounce::Scene& scene,
       const RendererSettings& settings);

  RendererSettings settings;
  std::unique_ptr<vk::Context> context;  // before what uses it: destroyed last
  bounce::Scene scene;                   // the renderer's own copy, which the frame refers to
  std::unique_ptr<GpuScene> gpuScene;
  std::unique_ptr<HybridFrame> frame;
  uint64_t framesRendered = 0;
  bool externalDevice = false;            // renderGi() is allowed
  std::optional<AnimationPlayer> player;  // made at the first setAnimationTime
  // Every image requested (the display image first), and whether the frame's debug views are
  // those of a renderGi frame (requests of full-frame images left out).
  std::vector<std::string> requested{kDisplayImage};
  bool giRequests = false;

  // Makes the frame capture what `requested` names for the kind of frame about to render.
  void applyRequests(bool giFrame);
  // After a frame threw: forgets requests of names that frame does not know (the graph has
  // dropped them already), so that switching between render() and renderGi() does not bring
  // them back.
  void pruneRequests();
};

void Renderer::Impl::pruneRequests() {
  std::vector<std::string> known = frame->passNames();
  for (std::string& name : frame->resourceNames()) known.push_back(std::move(name));
  std::erase_if(requested, [&](const std::string& name) {
    if (giRequests && onlyInFullFrame(name)) return false;
    return std::find(known.begin(), known.end(), name) == known.end();
  });
}

void Renderer::Impl::applyRequests(bool giFrame) {
  if (giFrame == giRequests) return;
  frame->clearDebugViews();
  for (const std::string& name : requested)
    if (!giFrame || !onlyInFullFrame(name)) frame->requestDebugView(name);
  giRequests = giFrame;
}

Renderer::Impl::Impl(std::unique_ptr<vk::Context> ownContext, const bounce::Scene& source,
                     const RendererSettings& requested)
    : settings(requested), context(std::move(ownContext)), scene(source) {
  constexpr const char* where = "bounce::Renderer::create";
  HybridSettings hybrid = toInternal(settings, where);
  if (scene.materials.empty()) scene.materials.push_back(bounce::Material{.name = "default"});
  if (scene.instances.empty())
    fail("{}: the scene has no instances: add a mesh and an instance of it", where);
  validateScene(scene, scene.name.empty() ? std::string(where) : scene.name);
  gpuScene = std::make_unique<GpuScene>(*context, scene);
  frame = std::make_unique<HybridFrame>(*context, *gpuScene, scene, hybrid);
  frame->requestDebugView(kDisplayImage);
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&& other) noexcept = default;
Renderer& Renderer::operator=(Renderer&& other) noexcept = default;

Renderer Renderer::create(const Scene& scene, const RendererSettings& settings) {
  toInternal(settings, "bounce::Renderer::create");  // bad settings fail before device creation
  auto context = std::make_unique<vk::Context>(vk::contextOptionsFromEnvironment());
  return Renderer(std::make_unique<Impl>(std::move(context), scene.impl_->scene, settings));
}

Renderer Renderer::create(const ExternalDevice& device, const Scene& scene,
                          const RendererSettings& settings) {
  toInternal(settings, "bounce::Renderer::create");
  auto context = std::make_unique<vk::Context>(vk::AdoptedDevice{
      .instance = device.instance,
      .physicalDevice = device.physicalDevice,
      .device = device.device,
      .queue = device.queue,
      .queueFamily = device.queueFamilyIndex,
      .createInfo = device.createInfo,
  });
  auto impl = std::make_unique<Impl>(std::move(context), scene.impl_->scene, settings);
  impl->externalDevice = true;
  return Renderer(std::move(impl));
}

FrameStatistics Renderer::render(const Camera& camera) {
  bounce::Camera c = toInternal(camera, "bounce::Renderer::render");
  impl_->applyRequests(false);
  FrameStatistics statistics;
  statistics.frameIndex = impl_->framesRendered;
  std::vector<vk::PassTiming> timings;
  try {
    timings = impl_->frame->render(c);
  } catch (const Error&) {
    impl_->pruneRequests();
    throw;
  }
  for (vk::PassTiming& t : timings)
    statistics.passes.push_back({.name = std::move(t.name), .milliseconds = t.milliseconds});
  ++impl_->framesRendered;
  return statistics;
}

GiImage Renderer::renderGi(const Camera& camera, const HostGBuffer& gbuffer) {
  constexpr const char* where = "bounce::Renderer::renderGi";
  if (!impl_->externalDevice)
    fail(
        "{}: the renderer runs on a device Bounce created; bring your own G-buffer needs the "
        "host's device: Renderer::create(ExternalDevice, ...)",
        where);
  if (impl_->settings.gi == GiMode::None)
    fail("{}: settings.gi is None; bring your own G-buffer returns GI, so choose a GI mode", where);
  bounce::Camera c = toInternal(camera, where);
  HostGBufferImages host{toImported(gbuffer.depth), toImported(gbuffer.normal),
                         toImported(gbuffer.albedo), toImported(gbuffer.motion)};
  checkHostGBuffer(host, {impl_->frame->settings().width, impl_->frame->settings().height}, where);
  impl_->applyRequests(true);
  try {
    impl_->frame->renderGi(c, host);
  } catch (const Error&) {
    impl_->pruneRequests();
    throw;
  }
  ++impl_->framesRendered;
  graph::ResolvedImage gi = impl_->frame->giImage();
  return {.image = gi.image,
          .view = gi.view,
          .layout = gi.layout,
          .format = gi.format,
          .width = gi.extent.width,
          .height = gi.extent.height};
}

void Renderer::requestImage(const std::string& name) {
  if (name.empty()) fail("bounce::Renderer::requestImage: the name is empty");
  impl_->requested.push_back(name);
  if (!impl_->giRequests || !onlyInFullFrame(name)) impl_->frame->requestDebugView(name);
}

Image Renderer::readImage(const std::string& name) const {
  if (impl_->framesRendered == 0)
    fail("bounce::Renderer::readImage('{}'): no frame rendered yet: call render() first", name);
  try {
    return fromInternal(impl_->frame->debugViewImage(name));
  } catch (const Error& e) {
    fail(
        "bounce::Renderer::readImage('{}'): {} (requestImage(\"{}\") before render() captures "
        "it)",
        name, e.what(), name);
  }
}

void Renderer::setSunAndSky(const Sun& sun, const Sky& sky) {
  impl_->frame->setSunAndSky(toInternal(sun, "bounce::Renderer::setSunAndSky"),
                             toInternal(sky, "bounce::Renderer::setSunAndSky"));
}

void Renderer::setAnimationTime(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0)
    fail("bounce::Renderer::setAnimationTime: time {} s, expected a finite time >= 0", seconds);
  if (!impl_->player) {
    // The host's camera and sun rule: only what moves in the scene plays.
    SceneAnimation animation = impl_->scene.animation;
    animation.camera.reset();
    animation.timeOfDay.reset();
    impl_->player.emplace(impl_->scene, std::move(animation));
  }
  impl_->player->apply(*impl_->frame, float(seconds));
}

void Renderer::resetHistory() {
  impl_->frame->resetHistory();
}

const RendererSettings& Renderer::settings() const {
  return impl_->settings;
}

std::string Renderer::deviceName() const {
  return impl_->context->info().name;
}

}  // namespace bounce::api
