#include "vk/gpu_timer.h"

#include "vk/check.h"
#include "vk/memory_barrier.h"

namespace bounce::vk {

GpuTimer::GpuTimer(Context& context, uint32_t maxScopes)
    : context_(context), maxScopes_(maxScopes) {
  supported_ =
      context.info().timestampsOnComputeQueue && context.limits().timestampComputeAndGraphics;
  if (!supported_) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = maxScopes * 2;
  VK_CHECK(vkCreateQueryPool(context.device(), &ci, nullptr, &pool_));
  names_.reserve(maxScopes);
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(context_.device(), pool_, nullptr);
}

void GpuTimer::countRays(VkBuffer counter) {
  rayCounter_ = counter;
  if (counter && !rayReadback_)
    rayReadback_ = Buffer(context_, maxScopes_ * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          MemoryUse::Readback, "gpu-timer.ray-readback");
}

void GpuTimer::reset(VkCommandBuffer cmd) {
  names_.clear();
  open_ = false;
  if (supported_) vkCmdResetQueryPool(cmd, pool_, 0, maxScopes_ * 2);
  if (countingRays()) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                  VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, rayCounter_, 0, sizeof(uint32_t), 0u);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  }
}

void GpuTimer::begin(VkCommandBuffer cmd, const std::string& name) {
  if (open_) fail("GPU timer: scope '{}' begun inside '{}'", name, names_.back());
  if (names_.size() >= maxScopes_) fail("GPU timer: more than {} scopes", maxScopes_);
  names_.push_back(name);
  open_ = true;
  if (supported_)
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool_,
                         uint32_t(names_.size() - 1) * 2);
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (!open_) fail("GPU timer: end() without begin()");
  open_ = false;
  if (supported_)
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_,
                         uint32_t(names_.size() - 1) * 2 + 1);
  if (countingRays()) {
    // The scope's atomics land before the copy, and the copy reads before later scopes add.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy region{0, (names_.size() - 1) * sizeof(uint32_t), sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, rayCounter_, rayReadback_.handle(), 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
  }
}

std::vector<PassTiming> GpuTimer::read() {
  std::vector<PassTiming> timings;
  if (names_.empty()) return timings;
  std::vector<uint64_t> stamps(names_.size() * 2, 0);
  if (supported_)
    VK_CHECK(vkGetQueryPoolResults(
        context_.device(), pool_, 0, uint32_t(stamps.size()), stamps.size() * sizeof(uint64_t),
        stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  double nsPerTick = context_.info().timestampPeriodNs;
  for (size_t i = 0; i < names_.size(); ++i)
    timings.push_back({names_[i], double(stamps[2 * i + 1] - stamps[2 * i]) * nsPerTick * 1e-6});
  if (countingRays()) {
    const uint32_t* counts = rayReadback_.mappedAs<const uint32_t>();
    for (size_t i = 0; i < names_.size(); ++i)
      timings[i].rays = uint64_t(counts[i] - (i == 0 ? 0u : counts[i - 1]));
  }
  return timings;
}

}  // namespace bounce::vk
