// bounce::Denoiser (include/bounce/denoiser.h): a library denoiser (denoise/library_denoiser.h)
// on a frame graph of its own, fed from host memory each frame.
#include <bounce/denoiser.h>

#include <cstring>
#include <optional>
#include <span>

#include "core/error.h"
#include "denoise/denoise_upload.h"
#include "denoise/library_denoiser.h"
#include "graph/debug_view_image.h"
#include "graph/frame_graph.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "vk/context.h"

namespace bounce::api {

namespace {

constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr const char* kOutput = "denoiser.output";

bounce::DenoiserKind internalKind(DenoiserKind kind) {
  switch (kind) {
    case DenoiserKind::Svgf:
      return bounce::DenoiserKind::Svgf;
    case DenoiserKind::Reblur:
      return bounce::DenoiserKind::Reblur;
    case DenoiserKind::Hybrid:
      return bounce::DenoiserKind::Hybrid;
  }
  fail("bounce::Denoiser: unknown kind {}", int(kind));
}

void checkImage(const Image& image, uint32_t w, uint32_t h, const char* name) {
  if (image.width != w || image.height != h || image.rgba.size() != size_t(w) * h * 4)
    fail("bounce::Denoiser::denoise: {} is {}x{} with {} floats, expected {}x{} with {}", name,
         image.width, image.height, image.rgba.size(), w, h, size_t(w) * h * 4);
}

void checkFloats(const std::vector<float>& values, size_t expected, const char* name) {
  if (values.size() != expected)
    fail("bounce::Denoiser::denoise: {} has {} floats, expected {}", name, values.size(), expected);
}

}  // namespace

DenoiserKind denoiserKindFromName(const std::string& name) {
  if (name == "svgf") return DenoiserKind::Svgf;
  if (name == "reblur") return DenoiserKind::Reblur;
  if (name == "hybrid") return DenoiserKind::Hybrid;
  fail("unknown denoiser '{}': expected svgf, reblur or hybrid", name);
}

struct Denoiser::Impl {
  Impl(DenoiserKind k, uint32_t w, uint32_t h)
      : kind(k),
        width(w),
        height(h),
        context(vk::contextOptionsFromEnvironment()),
        scene(loadScene("cornell")),  // the denoisers read no scene; ComputePass binds one
        gpuScene(context, scene),
        denoiser(context, gpuScene, internalKind(k)),
        noisy(denoiseInputImage(context, kRgba16f, w, h, "denoiser.noisy")),
        depth(denoiseInputImage(context, VK_FORMAT_R32_SFLOAT, w, h, "denoiser.depth")),
        normals(denoiseInputImage(context, kRgba16f, w, h, "denoiser.normals")),
        motion(denoiseInputImage(context, VK_FORMAT_R16G16_SFLOAT, w, h, "denoiser.motion")),
        albedo(denoiseInputImage(context, kRgba16f, w, h, "denoiser.albedo")) {}

  graph::ImageHandle import(const std::string& name, vk::Image& image) {
    graph::ImportedImage imported =
        graph::ImportedImage::from(image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    imported.externalWrites = true;  // uploaded again between frames
    return graph.importImage(name, imported);
  }

  DenoiserKind kind;
  uint32_t width, height;
  vk::Context context;
  Scene scene;
  GpuScene gpuScene;
  LibraryDenoiser denoiser;
  vk::Image noisy, depth, normals, motion, albedo;
  bool dropHistory = false;
  graph::FrameGraph graph;  // after what it imports: destroyed first
};

Denoiser Denoiser::create(DenoiserKind kind, uint32_t width, uint32_t height) {
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    fail("bounce::Denoiser::create: size {}x{}, expected 1 to 8192 each", width, height);
  return Denoiser(std::make_unique<Impl>(kind, width, height));
}

Denoiser::Denoiser(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Denoiser::~Denoiser() = default;
Denoiser::Denoiser(Denoiser&& other) noexcept = default;
Denoiser& Denoiser::operator=(Denoiser&& other) noexcept = default;

Image Denoiser::denoise(const DenoiserFrame& frame) {
  Impl& d = *impl_;
  const uint32_t w = d.width, h = d.height;
  const size_t pixels = size_t(w) * h;
  checkImage(frame.noisy, w, h, "noisy");
  checkImage(frame.normal, w, h, "normal");
  checkFloats(frame.depth, pixels, "depth");
  checkFloats(frame.motion, 2 * pixels, "motion");
  const bool albedo = frame.albedo.width != 0;
  if (albedo) checkImage(frame.albedo, w, h, "albedo");

  vk::uploadImage(d.context, d.noisy, halfBytes(frame.noisy.rgba), 8);
  std::vector<uint8_t> depth(pixels * 4);
  std::memcpy(depth.data(), frame.depth.data(), depth.size());
  vk::uploadImage(d.context, d.depth, depth, 4);
  vk::uploadImage(d.context, d.normals, halfBytes(frame.normal.rgba), 8);
  vk::uploadImage(d.context, d.motion, halfBytes(frame.motion), 4);
  if (albedo) vk::uploadImage(d.context, d.albedo, halfBytes(frame.albedo.rgba), 8);

  d.graph.beginFrame();
  d.graph.requestDebugView(kOutput);
  DenoiseInputs in{d.import("denoiser.noisy", d.noisy), d.import("denoiser.depth", d.depth),
                   d.import("denoiser.normals", d.normals), d.import("denoiser.motion", d.motion)};
  if (albedo) in.albedo = d.import("denoiser.albedo", d.albedo);
  in.dropHistory = d.dropHistory;
  d.dropHistory = false;
  graph::ImageHandle out = d.graph.createImage(kOutput, {kRgba16f});
  d.denoiser.declare(d.graph, {w, h}, in, out);
  d.graph.allocate(d.context, {w, h});
  d.context.submitAndWait([&](VkCommandBuffer cmd) { d.graph.execute(cmd); });
  ImageRGBA32F result = graph::debugViewImage(d.graph.readDebugView(kOutput));
  Image image;
  image.width = w;
  image.height = h;
  image.rgba = std::move(result.pixels);
  return image;
}

void Denoiser::resetHistory() {
  impl_->dropHistory = true;
}

DenoiserKind Denoiser::kind() const {
  return impl_->kind;
}

uint32_t Denoiser::pipelineCount() const {
  return impl_->denoiser.pipelineCount();
}

std::string Denoiser::deviceName() const {
  return impl_->context.info().name;
}

}  // namespace bounce::api
