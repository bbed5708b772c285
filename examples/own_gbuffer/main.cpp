// Bring your own G-buffer: the host makes its own Vulkan device (as examples/own_device does),
// renders its own G-buffer of a scene it also gives Bounce (a white floor and a red wall in the
// sun; the G-buffer is analytic, computed on the CPU by intersecting the camera rays with the two
// quads, and uploaded to the four images of the contract in bounce/host_gbuffer.h), and asks
// Bounce for the diffuse GI (Renderer::renderGi). It reads the GI image back and checks: no NaN,
// not black, and colour bleeding: the floor beside the red wall is lit red by it. Exit code 0 on
// success, 1 with a message otherwise.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <bounce/bounce.h>
#include <vulkan/vulkan.h>

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(result) +
                             ")");
}

// A queue family with graphics and compute, as Bounce needs.
std::optional<uint32_t> graphicsComputeFamily(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & need) == need) return i;
  return std::nullopt;
}

// Whether the device supports every feature external_device.h lists.
bool supportsBounce(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(device, &properties);
  if (properties.apiVersion < VK_API_VERSION_1_3 || !graphicsComputeFamily(device)) return false;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(device, &f2);
  return f2.features.shaderInt64 && f12.bufferDeviceAddress && f12.scalarBlockLayout &&
         f12.timelineSemaphore && f13.synchronization2 && f13.dynamicRendering && f13.maintenance4;
}

// A discrete GPU first, then any other suitable device (lavapipe).
VkPhysicalDevice pickPhysicalDevice(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  for (VkPhysicalDevice device : devices) {
    if (!supportsBounce(device)) continue;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (!chosen || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) chosen = device;
  }
  if (!chosen) throw std::runtime_error("no Vulkan 1.3 device with the features Bounce needs");
  return chosen;
}

// The host's side of Vulkan that the example needs: memory, one-off command buffers, images.
struct Host {
  bounce::ExternalDevice device;
  VkCommandPool pool = VK_NULL_HANDLE;

  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags want) const {
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(device.physicalDevice, &properties);
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & want) == want) return i;
    throw std::runtime_error("no suitable memory type");
  }

  // Records with `record` into a fresh command buffer, submits it to the queue and waits.
  template <typename F>
  void submit(F record) {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device.device, &allocate, &cmd), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo submitInfo{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submitInfo.commandBufferCount = 1;
    submitInfo.pCommandBuffers = &cmd;
    check(vkQueueSubmit(device.queue, 1, &submitInfo, VK_NULL_HANDLE), "vkQueueSubmit");
    check(vkQueueWaitIdle(device.queue), "vkQueueWaitIdle");
    vkFreeCommandBuffers(device.device, pool, 1, &cmd);
  }
};

// A host-visible buffer for uploads and readbacks.
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;

  Buffer(const Host& host, VkDeviceSize size, VkBufferUsageFlags usage)
      : device(host.device.device) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    check(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer, &requirements);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex =
        host.memoryType(requirements.memoryTypeBits,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkAllocateMemory(device, &allocate, nullptr, &memory), "vkAllocateMemory");
    check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    check(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  }
  ~Buffer() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

 private:
  VkDevice device;
};

// One of the host's G-buffer images: a storage image (the contract) it fills by a copy.
struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkFormat format;
  uint32_t width, height;

  Image(const Host& host, VkFormat format, uint32_t width, uint32_t height)
      : format(format), width(width), height(height), device(host.device.device) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device, &info, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image, &requirements);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex =
        host.memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(device, &allocate, nullptr, &memory), "vkAllocateMemory");
    check(vkBindImageMemory(device, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check(vkCreateImageView(device, &viewInfo, nullptr, &view), "vkCreateImageView");
  }
  ~Image() {
    vkDestroyImageView(device, view, nullptr);
    vkDestroyImage(device, image, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  bounce::HostImage host() const { return {image, view, format, width, height}; }

 private:
  VkDevice device;
};

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = oldLayout;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// Fills `image` from tightly packed texels and leaves it in GENERAL, as the contract asks.
void upload(Host& host, const Image& image, const void* texels, size_t bytes) {
  Buffer staging(host, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.mapped, texels, bytes);
  host.submit([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image.image, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &region);
    imageBarrier(cmd, image.image, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
  });
}

uint16_t floatToHalf(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, 4);
  uint16_t sign = uint16_t((bits >> 16) & 0x8000u);
  int exponent = int((bits >> 23) & 0xffu) - 127 + 15;
  if (exponent <= 0) return sign;  // tiny values (and zero) flush to zero
  if (exponent >= 31) return uint16_t(sign | 0x7c00u);
  uint32_t mantissa = (bits >> 13) & 0x3ffu;
  return uint16_t(sign | (uint32_t(exponent) << 10) | mantissa);
}

float halfToFloat(uint16_t half) {
  uint32_t sign = uint32_t(half & 0x8000u) << 16;
  uint32_t exponent = (half >> 10) & 0x1fu;
  uint32_t mantissa = half & 0x3ffu;
  uint32_t bits;
  if (exponent == 0) {
    float value = std::ldexp(float(mantissa), -24);
    return sign ? -value : value;
  }
  if (exponent == 31)
    bits = sign | 0x7f800000u | (mantissa << 13);
  else
    bits = sign | ((exponent - 15 + 127) << 23) | (mantissa << 13);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

// ---- the host's scene and its G-buffer ------------------------------------------------------
// A white floor (y = 0) and a red wall (x = -1, facing +x) in the sun, seen from +x: what a host
// engine would rasterise. Bounce gets the same scene (for its rays) and the host's G-buffer.

constexpr uint32_t kWidth = 64, kHeight = 48;
constexpr float kFloorHalf = 2.0f, kWallHeight = 2.0f, kWallX = -1.0f;
const bounce::Vec3 kWhite{0.8f, 0.8f, 0.8f}, kRed{0.8f, 0.05f, 0.05f};

void addQuad(bounce::Scene& scene, const bounce::Vec3 (&corners)[4], bounce::Vec3 normal,
             bounce::Vec3 color) {
  bounce::MaterialId material =
      scene.addMaterial({.baseColor = color, .roughness = 1.0f, .doubleSided = true});
  bounce::Vec3 normals[4] = {normal, normal, normal, normal};
  uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  scene.addInstance(scene.addMesh(corners, normals, indices, material));
}

bounce::Scene makeScene() {
  bounce::Scene scene;
  float f = kFloorHalf;
  addQuad(scene, {{-f, 0, -f}, {-f, 0, f}, {f, 0, f}, {f, 0, -f}}, {0, 1, 0}, kWhite);
  addQuad(scene,
          {{kWallX, 0, -f}, {kWallX, kWallHeight, -f}, {kWallX, kWallHeight, f}, {kWallX, 0, f}},
          {1, 0, 0}, kRed);
  scene.setSun({.direction = {-0.8f, -1.0f, -0.3f}, .irradiance = 5.0f});
  scene.setSky({.radiance = {0.3f, 0.3f, 0.3f}});  // white light from above, everywhere
  return scene;
}

bounce::Camera makeCamera() {
  return {
      .position = {2.5f, 1.2f, 0.0f}, .target = {-1.0f, 0.5f, 0.0f}, .verticalFovDegrees = 60.0f};
}

struct V3 {
  float x, y, z;
};
V3 operator+(V3 a, V3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
V3 operator-(V3 a, V3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V3 operator*(V3 a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
float dot(V3 a, V3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
V3 cross(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
V3 normalize(V3 a) {
  return a * (1.0f / std::sqrt(dot(a, a)));
}
V3 v3(bounce::Vec3 v) {
  return {v.x, v.y, v.z};
}

// The host's G-buffer in the contract's encodings (bounce/host_gbuffer.h), by intersecting each
// pixel's camera ray with the floor and the wall: the camera model is Bounce's pinhole camera.
struct GBufferTexels {
  std::vector<float> depth;      // R32_SFLOAT
  std::vector<uint16_t> normal;  // R16G16B16A16_SFLOAT
  std::vector<uint8_t> albedo;   // R8G8B8A8_UNORM
  std::vector<uint16_t> motion;  // R16G16_SFLOAT
  std::vector<int> surface;      // 0 sky, 1 floor, 2 wall (for the checks)
};

GBufferTexels rasterise(const bounce::Camera& camera) {
  V3 position = v3(camera.position);
  V3 forward = normalize(v3(camera.target) - position);
  V3 right = normalize(cross(forward, v3(camera.up)));
  V3 up = cross(right, forward);
  float tanHalf = std::tan(camera.verticalFovDegrees * 3.14159265f / 360.0f);
  float aspect = float(kWidth) / float(kHeight);
  GBufferTexels g;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      float nx = 2.0f * (x + 0.5f) / kWidth - 1.0f, ny = 2.0f * (y + 0.5f) / kHeight - 1.0f;
      V3 dir = normalize(forward + right * (nx * tanHalf * aspect) - up * (ny * tanHalf));
      float t = INFINITY;
      int surface = 0;
      if (dir.y < 0.0f) {  // the floor
        float tf = -position.y / dir.y;
        V3 p = position + dir * tf;
        if (std::fabs(p.x) <= kFloorHalf && std::fabs(p.z) <= kFloorHalf) t = tf, surface = 1;
      }
      if (dir.x < 0.0f) {  // the wall
        float tw = (kWallX - position.x) / dir.x;
        V3 p = position + dir * tw;
        if (tw < t && p.y >= 0.0f && p.y <= kWallHeight && std::fabs(p.z) <= kFloorHalf)
          t = tw, surface = 2;
      }
      V3 n = surface == 1 ? V3{0, 1, 0} : surface == 2 ? V3{1, 0, 0} : V3{0, 0, 0};
      bounce::Vec3 color = surface == 1 ? kWhite : surface == 2 ? kRed : bounce::Vec3{0, 0, 0};
      g.depth.push_back(surface ? t * dot(dir, forward) : 0.0f);
      for (float c : {n.x, n.y, n.z, 0.0f}) g.normal.push_back(floatToHalf(c));
      for (float c : {color.x, color.y, color.z, 1.0f})
        g.albedo.push_back(uint8_t(std::lround(c * 255.0f)));
      g.motion.push_back(floatToHalf(0.0f));  // nothing moves
      g.motion.push_back(floatToHalf(0.0f));
      g.surface.push_back(surface);
    }
  return g;
}

// Reads Bounce's GI image back (RGBA16F) as floats: a copy after the barrier the contract asks.
std::vector<float> readGi(Host& host, const bounce::GiImage& gi) {
  if (gi.format != VK_FORMAT_R16G16B16A16_SFLOAT)
    throw std::runtime_error("the GI image has an unexpected format");
  size_t texels = size_t(gi.width) * gi.height;
  Buffer readback(host, texels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  host.submit([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, gi.image, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT, gi.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {gi.width, gi.height, 1};
    vkCmdCopyImageToBuffer(cmd, gi.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                           &region);
    VkBufferMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = readback.buffer;
    toHost.size = VK_WHOLE_SIZE;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &toHost;
    vkCmdPipelineBarrier2(cmd, &dependency);
  });
  std::vector<float> out(texels * 4);
  const uint16_t* halves = static_cast<const uint16_t*>(readback.mapped);
  for (size_t i = 0; i < out.size(); ++i) out[i] = halfToFloat(halves[i]);
  return out;
}

// The host's frame: its G-buffer, Bounce's GI on it, and the checks.
void runHost(const bounce::ExternalDevice& device) {
  Host host{device};
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = device.queueFamilyIndex;
  check(vkCreateCommandPool(device.device, &poolInfo, nullptr, &host.pool), "vkCreateCommandPool");
  struct PoolGuard {
    const Host& host;
    ~PoolGuard() { vkDestroyCommandPool(host.device.device, host.pool, nullptr); }
  } poolGuard{host};

  bounce::Scene scene = makeScene();
  bounce::Camera camera = makeCamera();
  GBufferTexels texels = rasterise(camera);
  Image depth(host, VK_FORMAT_R32_SFLOAT, kWidth, kHeight);
  Image normal(host, VK_FORMAT_R16G16B16A16_SFLOAT, kWidth, kHeight);
  Image albedo(host, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight);
  Image motion(host, VK_FORMAT_R16G16_SFLOAT, kWidth, kHeight);
  upload(host, depth, texels.depth.data(), texels.depth.size() * 4);
  upload(host, normal, texels.normal.data(), texels.normal.size() * 2);
  upload(host, albedo, texels.albedo.data(), texels.albedo.size());
  upload(host, motion, texels.motion.data(), texels.motion.size() * 2);

  bounce::RendererSettings settings = bounce::presetSettings(bounce::Preset::Desktop);
  settings.width = kWidth;
  settings.height = kHeight;
  settings.gi = bounce::GiMode::Evolve;
  bounce::Renderer renderer = bounce::Renderer::create(device, scene, settings);
  bounce::HostGBuffer gbuffer{depth.host(), normal.host(), albedo.host(), motion.host()};
  constexpr int kFrames = 8;
  bounce::GiImage gi;
  for (int frame = 0; frame < kFrames; ++frame) gi = renderer.renderGi(camera, gbuffer);
  if (gi.width != kWidth || gi.height != kHeight)
    throw std::runtime_error("the GI image has the wrong size");
  std::vector<float> rgba = readGi(host, gi);

  // No NaN, not black, and colour bleeding: the floor within 0.5 m of the red wall gets red
  // light from it (its GI is redder than green), while the white floor over 1.5 m from it is much
  // less so.
  double sum = 0.0, nearRed = 0.0, nearGreen = 0.0, farRed = 0.0, farGreen = 0.0;
  int nearCount = 0, farCount = 0;
  V3 position = v3(camera.position);
  V3 forward = normalize(v3(camera.target) - position);
  float tanHalf = std::tan(camera.verticalFovDegrees * 3.14159265f / 360.0f);
  V3 right = normalize(cross(forward, v3(camera.up)));
  V3 up = cross(right, forward);
  for (uint32_t i = 0; i < kWidth * kHeight; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(rgba[4 * i + c]))
        throw std::runtime_error("the GI image has NaN or infinite values");
      sum += rgba[4 * i + c];
    }
    if (texels.surface[i] != 1) continue;
    float nx = 2.0f * (i % kWidth + 0.5f) / kWidth - 1.0f;
    float ny = 2.0f * (i / kWidth + 0.5f) / kHeight - 1.0f;
    V3 dir =
        normalize(forward + right * (nx * tanHalf * float(kWidth) / kHeight) - up * (ny * tanHalf));
    V3 p = position + dir * (texels.depth[i] / dot(dir, forward));
    float fromWall = p.x - kWallX;
    if (fromWall < 0.5f) {
      nearRed += rgba[4 * i], nearGreen += rgba[4 * i + 1], ++nearCount;
    } else if (fromWall > 1.5f) {
      farRed += rgba[4 * i], farGreen += rgba[4 * i + 1], ++farCount;
    }
  }
  double mean = sum / (3.0 * kWidth * kHeight);
  if (!(mean > 1e-4)) throw std::runtime_error("the GI image is black");
  if (nearCount == 0 || farCount == 0)
    throw std::runtime_error("the view shows no floor near or far from the wall");
  double nearRatio = nearRed / std::max(nearGreen, 1e-9);
  double farRatio = farRed / std::max(farGreen, 1e-9);
  std::printf(
      "own_gbuffer: %ux%u on %s, %d frames of renderGi: mean GI %.4f; floor GI red/green near the "
      "red wall %.2f (%d px), far from it %.2f (%d px)\n",
      kWidth, kHeight, renderer.deviceName().c_str(), kFrames, mean, nearRatio, nearCount, farRatio,
      farCount);
  if (!(nearRatio > 1.5))
    throw std::runtime_error("no colour bleeding: the floor's GI beside the red wall is not red");
  if (!(nearRatio > 1.3 * farRatio))
    throw std::runtime_error("the floor's GI is no redder beside the red wall than far from it");

  // The same renderer still renders Bounce's own full frame (its own G-buffer, sky, tonemap).
  renderer.render(camera);
  bounce::Image display = renderer.readImage();
  if (display.width != kWidth || display.height != kHeight)
    throw std::runtime_error("render() after renderGi() gave the wrong image");
}

}  // namespace

int main() {
  VkInstance instance = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  int exitCode = 0;
  try {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "bounce own_gbuffer example";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    check(vkCreateInstance(&instanceInfo, nullptr, &instance), "vkCreateInstance");

    VkPhysicalDevice physicalDevice = pickPhysicalDevice(instance);
    uint32_t family = *graphicsComputeFamily(physicalDevice);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = family;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    // What bounce/external_device.h lists.
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                         &f13};
    f12.bufferDeviceAddress = VK_TRUE;
    f12.scalarBlockLayout = VK_TRUE;
    f12.timelineSemaphore = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    f2.features.shaderInt64 = VK_TRUE;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    check(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), "vkCreateDevice");
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(device, family, 0, &queue);

    runHost({.instance = instance,
             .physicalDevice = physicalDevice,
             .device = device,
             .queue = queue,
             .queueFamilyIndex = family,
             .createInfo = &deviceInfo});

    // The device is still the host's and still works.
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence after the renderer");
    check(vkQueueSubmit(queue, 0, nullptr, fence), "vkQueueSubmit after the renderer");
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    vkDestroyFence(device, fence, nullptr);
    std::printf("own_gbuffer: the host's device outlived the renderer\n");
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "own_gbuffer: bounce: %s\n", e.what());
    exitCode = 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_gbuffer: %s\n", e.what());
    exitCode = 1;
  }
  if (device) vkDestroyDevice(device, nullptr);
  if (instance) vkDestroyInstance(instance, nullptr);
  return exitCode;
}
