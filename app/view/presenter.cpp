#include "presenter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <backends/imgui_impl_vulkan.h>
#include <stb_image_write.h>

#include "core/error.h"
#include "vk/check.h"

namespace bounce::view {

namespace {

// The sRGB byte of a linear value in [0, 1], from a table over 2^16 steps (a pow per channel
// would cost tens of milliseconds a frame at 1080p); the finest sRGB step near black is 1/3295
// in linear terms, coarser than the table's 1/65535.
uint8_t toSrgbByte(float linear) {
  static const std::vector<uint8_t> table = [] {
    std::vector<uint8_t> t(65536);
    for (size_t i = 0; i < t.size(); ++i) {
      const float v = float(i) / 65535.0f;
      const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
      t[i] = uint8_t(std::lround(255.0f * s));
    }
    return t;
  }();
  const float v = std::clamp(std::isfinite(linear) ? linear : 0.0f, 0.0f, 1.0f);
  return table[size_t(v * 65535.0f + 0.5f)];
}

// Lost devices and surfaces end the viewer with a message that says so (runViewer).
void checkSurfaceResult(VkResult r) {
  if (r == VK_ERROR_DEVICE_LOST) fail("presenting: VK_ERROR_DEVICE_LOST");
  if (r == VK_ERROR_SURFACE_LOST_KHR) fail("presenting: VK_ERROR_SURFACE_LOST_KHR");
}

// One image barrier (synchronization2).
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

// The largest rectangle of the image's aspect ratio centred in the window (letterbox).
VkOffset3D fitOffsets(uint32_t imageW, uint32_t imageH, VkExtent2D window, VkOffset3D* end) {
  const double scale = std::min(double(window.width) / imageW, double(window.height) / imageH);
  const int32_t w = std::max(1, int32_t(std::lround(imageW * scale)));
  const int32_t h = std::max(1, int32_t(std::lround(imageH * scale)));
  const int32_t x = (int32_t(window.width) - w) / 2, y = (int32_t(window.height) - h) / 2;
  *end = {x + w, y + h, 1};
  return {x, y, 0};
}

}  // namespace

Presenter::Presenter(vk::Context& context, Swapchain& swapchain)
    : context_(context), swapchain_(swapchain) {
  VkDevice device = context_.device();
  try {
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = context_.queueFamily();
    VK_CHECK(vkCreateCommandPool(device, &pool, nullptr, &commandPool_));
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = commandPool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(device, &ai, &cmd_));
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device, &fi, nullptr, &fence_));
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VK_CHECK(vkCreateSemaphore(device, &si, nullptr, &imageAvailable_));
  } catch (...) {
    release();
    throw;
  }
}

Presenter::~Presenter() {
  release();
}

void Presenter::release() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  staging_.reset();
  display_.reset();
  windowReadback_.reset();
  vkDestroySemaphore(device, imageAvailable_, nullptr);
  vkDestroyFence(device, fence_, nullptr);
  vkDestroyCommandPool(device, commandPool_, nullptr);
  imageAvailable_ = VK_NULL_HANDLE;
  fence_ = VK_NULL_HANDLE;
  commandPool_ = VK_NULL_HANDLE;
}

// Made at start and when the shown image's size changes (a resize, a view of another size):
// never per frame.
bool Presenter::ensureDisplayResources(uint32_t width, uint32_t height) {
  if (display_.handle() && display_.width() == width && display_.height() == height) return false;
  context_.waitIdle();
  staging_ = vk::Buffer(context_, VkDeviceSize(width) * height * 4,
                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::Upload, "view-staging");
  display_ = vk::Image(context_, VK_FORMAT_R8G8B8A8_UNORM, width, height, 1, 1,
                       VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                           VK_IMAGE_USAGE_SAMPLED_BIT,  // vk::Image makes a view
                       "view-display", VK_IMAGE_VIEW_TYPE_2D);
  return true;
}

// The view's linear values as the .png writer encodes them: clamped to [0, 1], sRGB.
bool Presenter::upload(const ImageRGBA32F& image) {
  const bool made = ensureDisplayResources(uint32_t(image.width), uint32_t(image.height));
  uint8_t* out = staging_.mappedAs<uint8_t>();
  const size_t pixels = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < 3; ++c) out[4 * i + c] = toSrgbByte(image.pixels[4 * i + c]);
    out[4 * i + 3] = 255;
  }
  return made;
}

Presenter::Outcome Presenter::present(ImDrawData* ui, bool captureWindow) {
  Outcome outcome;
  VkDevice device = context_.device();
  uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(device, swapchain_.handle(), 1000000000ull,
                                            imageAvailable_, VK_NULL_HANDLE, &index);
  checkSurfaceResult(acquired);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    outcome.recreate = true;
    return outcome;
  }
  if (acquired == VK_TIMEOUT || acquired == VK_NOT_READY) return outcome;
  if (acquired == VK_SUBOPTIMAL_KHR)
    outcome.recreate = true;
  else
    VK_CHECK(acquired);

  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &bi));
  const VkImage target = swapchain_.image(index);
  const VkExtent2D extent = swapchain_.extent();
  imageBarrier(cmd_, display_.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {display_.width(), display_.height(), 1};
  vkCmdCopyBufferToImage(cmd_, staging_.handle(), display_.handle(),
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  imageBarrier(cmd_, display_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_READ_BIT);
  // The acquire semaphore is waited for at the transfer stage: the barrier's first scope.
  imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkClearColorValue black{};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
  imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(display_.width()), int32_t(display_.height()), 1};
  blit.dstOffsets[0] = fitOffsets(display_.width(), display_.height(), extent, &blit.dstOffsets[1]);
  vkCmdBlitImage(cmd_, display_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);

  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = swapchain_.renderPass();
  rp.framebuffer = swapchain_.framebuffer(index);
  rp.renderArea.extent = extent;
  vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ui, cmd_);
  vkCmdEndRenderPass(cmd_);

  if (captureWindow && swapchain_.canReadBack()) {
    // The render pass's dependency to EXTERNAL makes its writes and final layout available to
    // the transfer stage.
    imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                 VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    windowReadback_ =
        vk::Buffer(context_, VkDeviceSize(extent.width) * extent.height * 4,
                   VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "window-readback");
    VkBufferImageCopy back{};
    back.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    back.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           windowReadback_.handle(), 1, &back);
    imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                 VK_PIPELINE_STAGE_2_NONE, 0);
    capturedExtent_ = extent;
  }
  VK_CHECK(vkEndCommandBuffer(cmd_));

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = imageAvailable_;
  wait.stageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = swapchain_.renderFinished(index);
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cb.commandBuffer = cmd_;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cb;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  VK_CHECK(vkResetFences(device, 1, &fence_));
  VK_CHECK(vkQueueSubmit2(context_.queue(), 1, &submit, fence_));

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  VkSemaphore finished = swapchain_.renderFinished(index);
  VkSwapchainKHR handle = swapchain_.handle();
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &finished;
  present.swapchainCount = 1;
  present.pSwapchains = &handle;
  present.pImageIndices = &index;
  VkResult presented = vkQueuePresentKHR(context_.queue(), &present);
  // The renderer waits for each of its frames anyway: one frame in flight costs nothing here.
  VK_CHECK(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX));
  checkSurfaceResult(presented);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
    outcome.recreate = true;
  else
    VK_CHECK(presented);
  outcome.presented = true;
  return outcome;
}

void Presenter::writeWindowCapture(const std::string& path) const {
  if (!windowReadback_) fail("{}: no window image was captured", path);
  const VkExtent2D e = capturedExtent_;
  std::vector<uint8_t> rgba(size_t(e.width) * e.height * 4);
  const uint8_t* in = windowReadback_.mappedAs<uint8_t>();
  const bool bgra = swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM;
  for (size_t i = 0; i < size_t(e.width) * e.height; ++i) {
    rgba[4 * i + 0] = in[4 * i + (bgra ? 2 : 0)];
    rgba[4 * i + 1] = in[4 * i + 1];
    rgba[4 * i + 2] = in[4 * i + (bgra ? 0 : 2)];
    rgba[4 * i + 3] = 255;
  }
  if (!stbi_write_png(path.c_str(), int(e.width), int(e.height), 4, rgba.data(), int(e.width) * 4))
    fail("--window-screenshot '{}': cannot write the file", path);
  std::printf("bounce view: window %ux%u -> %s\n", e.width, e.height, path.c_str());
}

}  // namespace bounce::view
