// Shows an image in the window: the view's linear values encoded as 8-bit sRGB (as the .png
// writer does) and uploaded, blitted letterboxed on black into the acquired swapchain image, the
// UI drawn over it (Swapchain::renderPass), presented; on request the presented image is read
// back (a window screenshot). One frame in flight: the renderer waits for each of its frames
// anyway. Its staging buffer and image are made at the first upload and when the image's size
// changes, never per frame.
#pragma once
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "swapchain.h"
#include "tools/image_io.h"
#include "vk/context.h"
#include "vk/resources.h"

struct ImDrawData;

namespace bounce::view {

class Presenter {
 public:
  Presenter(vk::Context& context, Swapchain& swapchain);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // The image the next present() shows (rows top to bottom, linear values; clamped to [0, 1]).
  // Returns true when it made new resources for it (the first image, a new size).
  bool upload(const ImageRGBA32F& image);

  struct Outcome {
    bool presented = false;  // false: acquire timed out or the swapchain was out of date
    bool recreate = false;   // VK_ERROR_OUT_OF_DATE_KHR or VK_SUBOPTIMAL_KHR: recreate it
  };
  // Acquires, records, submits, presents and waits. `ui` is Dear ImGui's draw data for this
  // frame. A lost device or surface throws bounce::Error naming the VkResult.
  Outcome present(ImDrawData* ui, bool captureWindow);
  // Writes the last captured window image as a .png (RGB; the swapchain's BGRA swizzled).
  void writeWindowCapture(const std::string& path) const;

 private:
  void release();
  bool ensureDisplayResources(uint32_t width, uint32_t height);

  vk::Context& context_;
  Swapchain& swapchain_;
  vk::Buffer staging_;
  vk::Image display_;
  vk::Buffer windowReadback_;
  VkExtent2D capturedExtent_{0, 0};
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
};

}  // namespace bounce::view
