// Named GPU timestamps: begin(cmd, "pass") / end(cmd) around each pass, read back in
// milliseconds after the work completes. Query slots are allocated once (no per-frame
// allocation). With countRays(), each scope also reports the rays its shaders counted.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/resources.h"

namespace bounce::vk {

struct PassTiming {
  std::string name;
  double milliseconds = 0.0;
  std::optional<uint64_t> rays;  // set while counting rays (GpuTimer::countRays)
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

  // Rays per scope from a device counter (a uint that shaders increment, e.g. GpuScene::
  // rayCounter()): reset() zeroes it and end() copies it to a readback slot, so a scope's rays
  // are the difference to the previous scope's copy. The barriers this adds around every scope
  // serialise the passes a little; time without counting for the best figures. Pass a null
  // handle to stop. The readback buffer is made here, once.
  void countRays(VkBuffer counter);
  bool countingRays() const { return rayCounter_ != VK_NULL_HANDLE; }

 private:
  Context& context_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t maxScopes_;
  bool supported_ = false;
  std::vector<std::string> names_;
  bool open_ = false;
  VkBuffer rayCounter_ = VK_NULL_HANDLE;
  Buffer rayReadback_;  // maxScopes_ uints
};

}  // namespace bounce::vk
