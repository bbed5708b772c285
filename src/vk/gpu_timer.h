// Named GPU timestamps: begin(cmd, "pass") / end(cmd) around each pass, read back in
// milliseconds after the work completes. Query slots are allocated once (no per-frame
// allocation).
#pragma once
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace bounce::vk {

struct PassTiming {
  std::string name;
  double milliseconds = 0.0;
};

class GpuTimer {
 public:
  GpuTimer(Context& context, uint32_t maxScopes = 128);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  bool available() const { return supported_; }
  void reset(VkCommandBuffer cmd);  // before the first scope of a submission
  void begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd);
  // After the submission finished: one entry per scope, in recording order.
  std::vector<PassTiming> read();

 private:
  Context& context_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t maxScopes_;
  bool supported_ = false;
  std::vector<std::string> names_;
  bool open_ = false;
};

}  // namespace bounce::vk
