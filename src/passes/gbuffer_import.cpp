#include "passes/gbuffer_import.h"

#include "core/error.h"

namespace bounce {

using graph::Access;

namespace {

const char* formatName(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
      return "VK_FORMAT_R32_SFLOAT";
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return "VK_FORMAT_R16G16B16A16_SFLOAT";
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "VK_FORMAT_R8G8B8A8_UNORM";
    case VK_FORMAT_R8G8B8A8_SRGB:
      return "VK_FORMAT_R8G8B8A8_SRGB";
    case VK_FORMAT_R16G16_SFLOAT:
      return "VK_FORMAT_R16G16_SFLOAT";
    case VK_FORMAT_R32G32_SFLOAT:
      return "VK_FORMAT_R32G32_SFLOAT";
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return "VK_FORMAT_R32G32B32A32_SFLOAT";
    case VK_FORMAT_D32_SFLOAT:
      return "VK_FORMAT_D32_SFLOAT";
    case VK_FORMAT_B8G8R8A8_UNORM:
      return "VK_FORMAT_B8G8R8A8_UNORM";
    case VK_FORMAT_UNDEFINED:
      return "VK_FORMAT_UNDEFINED";
    default:
      return nullptr;
  }
}

std::string describeFormat(VkFormat format) {
  const char* name = formatName(format);
  return name ? std::string(name) : "VkFormat " + std::to_string(int(format));
}

void checkImage(const graph::ImportedImage& image, const char* name, VkFormat expected,
                VkExtent2D resolution, const char* where) {
  if (!image.image || !image.view)
    fail("{}: the host's {} image has no VkImage or no VkImageView", where, name);
  if (image.format != expected)
    fail("{}: the host's {} image has format {}; it must be {}", where, name,
         describeFormat(image.format), describeFormat(expected));
  if (image.extent.width != resolution.width || image.extent.height != resolution.height)
    fail("{}: the host's {} image is {}x{}; it must be the render resolution {}x{}", where, name,
         image.extent.width, image.extent.height, resolution.width, resolution.height);
  if (image.layers != 1 || image.mips != 1)
    fail("{}: the host's {} image has {} layers and {} mips; it must have one of each", where, name,
         image.layers, image.mips);
}

graph::ImportedImage asImported(graph::ImportedImage image) {
  image.layout = VK_IMAGE_LAYOUT_GENERAL;
  image.externalWrites = true;
  return image;
}

}  // namespace

void checkHostGBuffer(const HostGBufferImages& host, VkExtent2D resolution, const char* where) {
  checkImage(host.depth, "depth", VK_FORMAT_R32_SFLOAT, resolution, where);
  checkImage(host.normal, "normal", VK_FORMAT_R16G16B16A16_SFLOAT, resolution, where);
  checkImage(host.albedo, "albedo", VK_FORMAT_R8G8B8A8_UNORM, resolution, where);
  checkImage(host.motion, "motion", VK_FORMAT_R16G16_SFLOAT, resolution, where);
}

GBufferImportPass::GBufferImportPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/gbuffer_import", gpu::GBUFFER_IMPORT_BINDING_COUNT) {}

GBuffer GBufferImportPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                   const HostGBufferImages& host) {
  checkHostGBuffer(host, frame.resolution, "gbuffer-import");
  graph::ImageHandle depth = graph.importImage("host.depth", asImported(host.depth));
  graph::ImageHandle normal = graph.importImage("host.normal", asImported(host.normal));
  graph::ImageHandle albedo = graph.importImage("host.albedo", asImported(host.albedo));
  graph::ImageHandle motion = graph.importImage("host.motion", asImported(host.motion));

  GBuffer g = GBuffer::create(graph);
  graph.addPass("gbuffer-import", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(depth, Access::StorageRead, gpu::GBUFFER_IMPORT_BINDING_HOST_DEPTH)
      .read(normal, Access::StorageRead, gpu::GBUFFER_IMPORT_BINDING_HOST_NORMAL)
      .read(albedo, Access::StorageRead, gpu::GBUFFER_IMPORT_BINDING_HOST_ALBEDO)
      .read(motion, Access::StorageRead, gpu::GBUFFER_IMPORT_BINDING_HOST_MOTION)
      .write(g.baseColor, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_BASE_COLOR)
      .write(g.normals, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_NORMALS)
      .write(g.depth.current, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_DEPTH)
      .write(g.uv, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_UV)
      .write(g.velocity, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_VELOCITY)
      .write(g.emissive, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_EMISSIVE)
      .write(g.flags, Access::StorageWrite, gpu::GBUFFER_IMPORT_BINDING_FLAGS)
      .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), frame.resolution);
      });
  return g;
}

}  // namespace bounce
