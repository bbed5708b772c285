// The window's swapchain and what draws into its images: a render pass that keeps the image's
// contents (the frame is blitted in first) and draws the UI over it, ending in PRESENT_SRC, and
// one framebuffer per image. Recreated on resize and whenever acquire or present says the
// surface changed (VK_ERROR_OUT_OF_DATE_KHR, VK_SUBOPTIMAL_KHR).
#pragma once
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace bounce::view {

class Swapchain {
 public:
  Swapchain(VkPhysicalDevice physicalDevice, VkDevice device, VkSurfaceKHR surface);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // (Re)creates the swapchain for a framebuffer of width x height pixels (the surface's current
  // extent wins where it has one). The device must be idle. Returns false when the surface has
  // zero area (a minimised window): there is nothing to present to until it has some again.
  bool recreate(uint32_t width, uint32_t height);
  bool valid() const { return swapchain_ != VK_NULL_HANDLE; }

  VkSwapchainKHR handle() const { return swapchain_; }
  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_; }
  // The render pass that draws over a blitted image: its attachment starts in
  // TRANSFER_DST_OPTIMAL (loaded) and ends in PRESENT_SRC_KHR. Compatible across recreations.
  VkRenderPass renderPass() const { return renderPass_; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkFramebuffer framebuffer(uint32_t i) const { return framebuffers_[i]; }
  // Signalled when image i's drawing is done; presentation waits for it.
  VkSemaphore renderFinished(uint32_t i) const { return renderFinished_[i]; }
  // Whether the images can be copied from (a window screenshot).
  bool canReadBack() const { return transferSrc_; }

 private:
  void createRenderPass();
  void destroyImages();

  VkPhysicalDevice physicalDevice_;
  VkDevice device_;
  VkSurfaceKHR surface_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  uint32_t minImageCount_ = 2;
  bool transferSrc_ = false;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> renderFinished_;
};

}  // namespace bounce::view
