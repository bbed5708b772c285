#include <bounce/renderer.h>

#include <bounce/external_device.h>

#include "api/convert.h"
#include "api/scene_impl.h"
#include "core/error.h"
#include "rt/gpu_scene.h"
#include "frame/hybrid_frame.h"
#include "vk/context.h"

namespace bounce::api {

namespace {

constexpr const char* kDisplayImage = "tonemap";

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
};

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
  return Renderer(std::make_unique<Impl>(std::move(context), scene.impl_->scene, settings));
}

FrameStatistics Renderer::render(const Camera& camera) {
  bounce::Camera c = toInternal(camera, "bounce::Renderer::render");
  FrameStatistics statistics;
  statistics.frameIndex = impl_->framesRendered;
  for (vk::PassTiming& t : impl_->frame->render(c))
    statistics.passes.push_back({.name = std::move(t.name), .milliseconds = t.milliseconds});
  ++impl_->framesRendered;
  return statistics;
}

void Renderer::requestImage(const std::string& name) {
  if (name.empty()) fail("bounce::Renderer::requestImage: the name is empty");
  impl_->frame->requestDebugView(name);
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
