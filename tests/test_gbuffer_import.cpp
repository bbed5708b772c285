// Bring your own G-buffer (passes/gbuffer_import.h) on lavapipe:
//   - Bounce's own GBuffer of the Cornell box, decoded on the CPU to the host contract
//     (bounce/host_gbuffer.h) and fed back through `gbuffer-import`, gives the same gi.diffuse
//     as the normal frame (same camera, same frame count, same random numbers): the physical
//     check that the import decodes the contract right. A host depth off by 20% does not.
//   - a host image of the wrong format or extent is a bounce::Error naming the image; the frame
//     then still renders, switching between full frames and renderGi frames.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "harness.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

constexpr uint32_t kWidth = 48;
constexpr uint32_t kHeight = 32;
constexpr int kFrames = 8;

// A host image: storage, filled from `texels` and left in GENERAL, as the contract asks.
vk::Image hostImage(vk::Context& context, VkFormat format, std::span<const std::byte> texels,
                    const std::string& name) {
  vk::Image image(context, format, kWidth, kHeight, 1, 1,
                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name,
                  VK_IMAGE_VIEW_TYPE_2D);
  vk::Buffer staging(context, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     vk::MemoryUse::Upload, name + ".staging");
  std::memcpy(staging.mapped(), texels.data(), texels.size());
  context.submitAndWait([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.handle();
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {kWidth, kHeight, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    vkCmdPipelineBarrier2(cmd, &dependency);
  });
  return image;
}

graph::ImportedImage imported(const vk::Image& image) {
  return graph::ImportedImage::from(image, VK_IMAGE_LAYOUT_GENERAL);
}

// Bounce's GBuffer of one frame, decoded to the host contract.
struct HostTexels {
  std::vector<float> depth;      // R32F
  std::vector<uint16_t> normal;  // RGBA16F
  std::vector<uint8_t> albedo;   // RGBA8
  std::vector<uint16_t> motion;  // RG16F
};

HostTexels decodeToHost(const ImageRGBA32F& baseColor, const ImageRGBA32F& normals,
                        const ImageRGBA32F& depth, const ImageRGBA32F& velocity, float depthScale) {
  HostTexels t;
  size_t n = size_t(kWidth) * kHeight;
  for (size_t i = 0; i < n; ++i) {
    t.depth.push_back(depth.pixels[4 * i] * depthScale);
    glm::vec3 normal(0.0f);
    if (depth.pixels[4 * i] > 0.0f)
      normal = test::decodeOctahedral({normals.pixels[4 * i], normals.pixels[4 * i + 1]});
    for (int c = 0; c < 3; ++c) t.normal.push_back(glm::packHalf1x16(normal[c]));
    t.normal.push_back(glm::packHalf1x16(0.0f));
    for (int c = 0; c < 3; ++c)
      t.albedo.push_back(
          uint8_t(std::lround(std::clamp(baseColor.pixels[4 * i + c], 0.0f, 1.0f) * 255.0f)));
    t.albedo.push_back(255);
    for (int c = 0; c < 2; ++c) t.motion.push_back(glm::packHalf1x16(velocity.pixels[4 * i + c]));
  }
  return t;
}

struct HostImages {
  vk::Image depth, normal, albedo, motion;
  HostGBufferImages imports() const {
    return {imported(depth), imported(normal), imported(albedo), imported(motion)};
  }
};

HostImages upload(vk::Context& context, const HostTexels& t) {
  return {hostImage(context, VK_FORMAT_R32_SFLOAT, std::as_bytes(std::span(t.depth)), "host.depth"),
          hostImage(context, VK_FORMAT_R16G16B16A16_SFLOAT, std::as_bytes(std::span(t.normal)),
                    "host.normal"),
          hostImage(context, VK_FORMAT_R8G8B8A8_UNORM, std::as_bytes(std::span(t.albedo)),
                    "host.albedo"),
          hostImage(context, VK_FORMAT_R16G16_SFLOAT, std::as_bytes(std::span(t.motion)),
                    "host.motion")};
}

HybridSettings giSettings() {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.gi = GiMode::Evolve;
  settings.width = kWidth;
  settings.height = kHeight;
  // A bring-your-own-G-buffer frame has no ReSTIR DI, so its gi.diffuse keeps the light of the
  // emitters DI would sample (the host lights its own direct light); Bounce's own frame does the
  // same only without DI. Same light on both sides, so the images must agree.
  settings.di.mode = DiMode::Off;
  return settings;
}

// gi.diffuse after kFrames frames of renderGi on `host`.
ImageRGBA32F importedGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                        const Camera& camera, const HostImages& host) {
  HybridFrame frame(context, gpuScene, scene, giSettings());
  frame.requestDebugView("gi.diffuse");
  for (int i = 0; i < kFrames; ++i) frame.renderGi(camera, host.imports());
  graph::ResolvedImage gi = frame.giImage();
  EXPECT_NE(gi.image, VK_NULL_HANDLE);
  EXPECT_NE(gi.view, VK_NULL_HANDLE);
  // GENERAL as the GI passes wrote it, or TRANSFER_SRC after the debug-view copy requested here.
  EXPECT_TRUE(gi.layout == VK_IMAGE_LAYOUT_GENERAL ||
              gi.layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)
      << gi.layout;
  EXPECT_EQ(gi.format, VK_FORMAT_R16G16B16A16_SFLOAT);
  EXPECT_EQ(gi.extent.width, kWidth);
  EXPECT_EQ(gi.extent.height, kHeight);
  return frame.debugViewImage("gi.diffuse");
}

TEST(GBufferImport, BouncesOwnGBufferFedBackGivesTheSameGi) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  Camera camera = effectiveCamera(scene);

  ImageRGBA32F baseColor, normals, depth, velocity, gi;
  {
    HybridFrame frame(context, gpuScene, scene, giSettings());
    for (const char* name : {"gbuffer.base-color", "gbuffer.normals", "gbuffer.depth",
                             "gbuffer.velocity", "gi.diffuse"})
      frame.requestDebugView(name);
    for (int i = 0; i < kFrames; ++i) frame.render(camera);
    baseColor = frame.debugViewImage("gbuffer.base-color");
    normals = frame.debugViewImage("gbuffer.normals");
    depth = frame.debugViewImage("gbuffer.depth");
    velocity = frame.debugViewImage("gbuffer.velocity");
    gi = frame.debugViewImage("gi.diffuse");
  }
  ASSERT_GT(test::meanLuminance(gi), 0.0) << "the normal frame's GI is black";

  HostImages host = upload(context, decodeToHost(baseColor, normals, depth, velocity, 1.0f));
  ImageRGBA32F giImported = importedGi(context, gpuScene, scene, camera, host);
  ASSERT_EQ(countNonFinitePixels(giImported), 0u);
  double relMse = relativeMeanSquaredError(giImported, gi);

  // The control: a host whose depth is 20% too far puts every surface in the wrong place.
  HostImages wrong = upload(context, decodeToHost(baseColor, normals, depth, velocity, 1.2f));
  double relMseWrong =
      relativeMeanSquaredError(importedGi(context, gpuScene, scene, camera, wrong), gi);
  std::printf("gbuffer-import: cornell %ux%u, %d frames: relMSE %.3g (host depth x1.2: %.3g)\n",
              kWidth, kHeight, kFrames, relMse, relMseWrong);
  // The normal frame run twice differs by relMSE ~1e-3 on lavapipe (`bounce render --scene
  // cornell --res 48x32 --frames 8 --view gi.diffuse` twice: 8.8e-4, 1.0e-3): the GI is not
  // bit-reproducible run to run, so the import is held to a few times that.
  EXPECT_LT(relMse, 5e-3);
  EXPECT_GT(relMseWrong, 10.0 * relMse);
  if (context.validationEnabled()) EXPECT_EQ(context.validationErrorCount(), 0u);
}

// The cache GI system runs on an imported GBuffer too: finite, not black.
TEST(GBufferImport, CacheGiRunsOnAnImportedGBuffer) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  Camera camera = effectiveCamera(scene);
  HybridSettings settings = giSettings();
  settings.gi = GiMode::Cache;
  HostTexels texels;
  {
    HybridFrame frame(context, gpuScene, scene, settings);
    for (const char* name :
         {"gbuffer.base-color", "gbuffer.normals", "gbuffer.depth", "gbuffer.velocity"})
      frame.requestDebugView(name);
    frame.render(camera);
    texels = decodeToHost(
        frame.debugViewImage("gbuffer.base-color"), frame.debugViewImage("gbuffer.normals"),
        frame.debugViewImage("gbuffer.depth"), frame.debugViewImage("gbuffer.velocity"), 1.0f);
  }
  HostImages host = upload(context, texels);
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("gi.diffuse");
  for (int i = 0; i < 3; ++i) frame.renderGi(camera, host.imports());
  ImageRGBA32F gi = frame.debugViewImage("gi.diffuse");
  EXPECT_EQ(countNonFinitePixels(gi), 0u);
  EXPECT_GT(test::meanLuminance(gi), 0.0);
  if (context.validationEnabled()) EXPECT_EQ(context.validationErrorCount(), 0u);
}

TEST(GBufferImport, WrongFormatOrExtentNamesTheImage) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, giSettings());
  HostTexels t;
  t.depth.assign(size_t(kWidth) * kHeight, 1.0f);
  t.normal.assign(size_t(kWidth) * kHeight * 4, glm::packHalf1x16(0.0f));
  t.albedo.assign(size_t(kWidth) * kHeight * 4, 128);
  t.motion.assign(size_t(kWidth) * kHeight * 2, glm::packHalf1x16(0.0f));
  HostImages host = upload(context, t);
  Camera camera = effectiveCamera(scene);

  auto expectError = [&](const HostGBufferImages& images, const std::string& needle) {
    try {
      frame.renderGi(camera, images);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  HostGBufferImages badFormat = host.imports();
  badFormat.normal.format = VK_FORMAT_R8G8B8A8_UNORM;
  expectError(badFormat,
              "normal image has format VK_FORMAT_R8G8B8A8_UNORM; it must be "
              "VK_FORMAT_R16G16B16A16_SFLOAT");
  HostGBufferImages badExtent = host.imports();
  badExtent.depth.extent.width = kWidth / 2;
  expectError(badExtent, "depth image is 24x32; it must be the render resolution 48x32");
  HostGBufferImages noView = host.imports();
  noView.motion.view = VK_NULL_HANDLE;
  expectError(noView, "motion image has no VkImage or no VkImageView");
  // The frame is still usable, and switches between the full frame and renderGi frames.
  EXPECT_NO_THROW(frame.renderGi(camera, host.imports()));
  EXPECT_NO_THROW(frame.render(camera));
  EXPECT_NO_THROW(frame.renderGi(camera, host.imports()));
  if (context.validationEnabled()) EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
