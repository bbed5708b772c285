// The Vulkan side of the frame graph: creating resources (at init and on resize only), resolving
// handles to Vulkan objects, recording passes with their barriers, timestamps and labels.
#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "graph/frame_graph.h"
#include "vk/check.h"
#include "vk/pipeline_log.h"

namespace bounce::graph {

namespace {

// Every image can be cleared (persistent and history start zeroed) and copied out (debug views);
// every buffer too, and can be reached through its device address.
constexpr VkImageUsageFlags kImageUsageAlways =
    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkBufferUsageFlags kBufferUsageAlways = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT;

bool covers(VkFlags have, VkFlags want) {
  return (have & want) == want;
}

void checkFormatSupport(const vk::Context& context, const std::string& name, VkFormat format,
                        VkImageUsageFlags usage) {
  VkImageFormatProperties properties;
  VkResult r =
      vkGetPhysicalDeviceImageFormatProperties(context.physicalDevice(), format, VK_IMAGE_TYPE_2D,
                                               VK_IMAGE_TILING_OPTIMAL, usage, 0, &properties);
  if (r != VK_SUCCESS)
    fail("image '{}': VkFormat {} does not support usage {:#x} (from its accesses) on {}", name,
         int(format), usage, context.info().name);
}

}  // namespace

FrameGraph::~FrameGraph() {
  if (context_) context_->waitIdle();
}

// ---- allocation -----------------------------------------------------------------------------

bool FrameGraph::matches(const PhysicalResource& physical, uint32_t index) const {
  const ResourceDecl& resource = resources_[index];
  if (resource.isImage) {
    const vk::Image& image = physical.image;
    VkExtent2D extent = resource.image.size.resolve(resolution_);
    return image.handle() && image.format() == resource.image.format &&
           image.width() == extent.width && image.height() == extent.height &&
           image.layers() == resource.image.layers && image.mips() == resource.image.mips &&
           covers(physical.usage, usage_[index]);
  }
  return physical.buffer && physical.buffer.size() == resource.buffer.size.resolve(resolution_) &&
         physical.memory == resource.buffer.memory && covers(physical.usage, usage_[index]);
}

void FrameGraph::create(PhysicalResource& physical, uint32_t index, const std::string& key) {
  const ResourceDecl& resource = resources_[index];
  physical = PhysicalResource{};
  if (resource.isImage) {
    const ImageDesc& desc = resource.image;
    VkExtent2D extent = desc.size.resolve(resolution_);
    VkImageUsageFlags usage = usage_[index] | kImageUsageAlways;
    checkFormatSupport(*context_, resource.name, desc.format, usage);
    VkImageViewType view = desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    physical.image = vk::Image(*context_, desc.format, extent.width, extent.height, desc.layers,
                               desc.mips, usage, key, view);
    physical.usage = usage;
  } else {
    VkBufferUsageFlags usage = usage_[index] | kBufferUsageAlways;
    physical.buffer = vk::Buffer(*context_, resource.buffer.size.resolve(resolution_), usage,
                                 resource.buffer.memory, key);
    physical.usage = usage;
    physical.memory = resource.buffer.memory;
  }
}

void FrameGraph::allocate(vk::Context& context, VkExtent2D renderResolution) {
  if (renderResolution.width == 0 || renderResolution.height == 0)
    fail("frame graph: render resolution {}x{} is empty", renderResolution.width,
         renderResolution.height);
  if (context_ && context_ != &context) fail("frame graph: allocate() with another vk::Context");
  context_ = &context;
  if (renderResolution.width != resolution_.width ||
      renderResolution.height != resolution_.height) {
    resetHistory();
    resolution_ = renderResolution;
  }
  if (!compiled_) compile();

  std::vector<std::string> created, toZero;
  for (uint32_t r = 0; r < resources_.size(); ++r) {
    const ResourceDecl& resource = resources_[r];
    if (!liveResources_[r] || resource.kind == ResourceKind::Imported) continue;
    std::string key = physicalKey(resource);
    PhysicalResource& physical = physical_[key];
    if (matches(physical, r)) continue;
    if (created.empty()) context.waitIdle();  // the old one may be in flight
    create(physical, r, key);
    states_.erase(key);
    if (resource.kind == ResourceKind::History) history_[resource.group].valid = false;
    if (resource.kind != ResourceKind::Transient) toZero.push_back(key);
    created.push_back(key);
  }
  if (created.empty()) return;
  if (!toZero.empty()) zeroNewResources(toZero);
  compiled_ = false;  // entry states changed: execute() compiles again
}

// Persistent and history resources start zeroed, so caches and first-frame history reads are
// deterministic; transients are written before they are read (validate() checks).
void FrameGraph::zeroNewResources(const std::vector<std::string>& keys) {
  context_->submitAndWait([&](VkCommandBuffer cmd) {
    for (const std::string& key : keys) {
      PhysicalResource& physical = physical_.at(key);
      ResourceState cleared{.writeStages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            .pendingWrites = VK_ACCESS_2_TRANSFER_WRITE_BIT};
      if (physical.buffer) {
        vkCmdFillBuffer(cmd, physical.buffer.handle(), 0, VK_WHOLE_SIZE, 0);
        states_[key] = cleared;
        continue;
      }
      VkImageSubresourceRange range{aspectsOf(physical.image.format()), 0, VK_REMAINING_MIP_LEVELS,
                                    0, VK_REMAINING_ARRAY_LAYERS};
      VkImageMemoryBarrier2 toGeneral{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
      toGeneral.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
      toGeneral.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      toGeneral.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      toGeneral.srcQueueFamilyIndex = toGeneral.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      toGeneral.image = physical.image.handle();
      toGeneral.subresourceRange = range;
      VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dependency.imageMemoryBarrierCount = 1;
      dependency.pImageMemoryBarriers = &toGeneral;
      vkCmdPipelineBarrier2(cmd, &dependency);
      if (isDepthFormat(physical.image.format())) {
        VkClearDepthStencilValue zero{};
        vkCmdClearDepthStencilImage(cmd, toGeneral.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1,
                                    &range);
      } else {
        VkClearColorValue zero{};
        vkCmdClearColorImage(cmd, toGeneral.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
      }
      cleared.layout = VK_IMAGE_LAYOUT_GENERAL;
      states_[key] = cleared;
    }
  });
}

// ---- recording ------------------------------------------------------------------------------

void FrameGraph::resolveResources() {
  resolved_.assign(resources_.size(), Resolved{});
  for (uint32_t r = 0; r < resources_.size(); ++r) {
    if (!liveResources_[r]) continue;
    const ResourceDecl& resource = resources_[r];
    Resolved& out = resolved_[r];
    if (resource.kind == ResourceKind::Imported) {
      const ImportedImage& i = resource.importedImage;
      const ImportedBuffer& b = resource.importedBuffer;
      out.image = {i.image, i.view, i.format, i.extent, i.layers, i.mips};
      out.buffer = {b.buffer, b.size, b.address, b.mapped};
      continue;
    }
    auto physical = physical_.find(physicalKey(resource));
    if (physical == physical_.end() || !matches(physical->second, r))
      fail(
          "frame graph: '{}' has no GPU {} matching this frame's declarations; call allocate() "
          "after declaring new or changed resources (frames never allocate)",
          resource.name, resource.isImage ? "image" : "buffer");
    const vk::Image& image = physical->second.image;
    const vk::Buffer& buffer = physical->second.buffer;
    if (resource.isImage)
      out.image = {image.handle(), image.view(), image.format(), {image.width(), image.height()},
                   image.layers(), image.mips()};
    else
      out.buffer = {buffer.handle(), buffer.size(), buffer.address(), buffer.mapped()};
  }
}

void FrameGraph::recordBarriers(VkCommandBuffer cmd, const std::vector<PlannedBarrier>& barriers) {
  if (barriers.empty()) return;
  imageBarriers_.clear();
  bufferBarriers_.clear();
  for (const PlannedBarrier& planned : barriers) {
    const Barrier& b = planned.barrier;
    const Resolved& resource = resolved_[planned.resource];
    if (planned.isImage) {
      VkImageMemoryBarrier2& out = imageBarriers_.emplace_back();
      out = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
      out.srcStageMask = b.srcStages;
      out.srcAccessMask = b.srcAccess;
      out.dstStageMask = b.dstStages;
      out.dstAccessMask = b.dstAccess;
      out.oldLayout = b.oldLayout;
      out.newLayout = b.newLayout;
      out.srcQueueFamilyIndex = out.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      out.image = resource.image.image;
      out.subresourceRange = {aspectsOf(resource.image.format), 0, VK_REMAINING_MIP_LEVELS, 0,
                              VK_REMAINING_ARRAY_LAYERS};
    } else {
      VkBufferMemoryBarrier2& out = bufferBarriers_.emplace_back();
      out = {VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
      out.srcStageMask = b.srcStages;
      out.srcAccessMask = b.srcAccess;
      out.dstStageMask = b.dstStages;
      out.dstAccessMask = b.dstAccess;
      out.srcQueueFamilyIndex = out.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      out.buffer = resource.buffer.buffer;
      out.size = VK_WHOLE_SIZE;
    }
  }
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = uint32_t(imageBarriers_.size());
  dependency.pImageMemoryBarriers = imageBarriers_.data();
  dependency.bufferMemoryBarrierCount = uint32_t(bufferBarriers_.size());
  dependency.pBufferMemoryBarriers = bufferBarriers_.data();
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void FrameGraph::recordPass(VkCommandBuffer cmd, const PassPlan& pass, vk::GpuTimer* timer) {
  recordBarriers(cmd, pass.barriers);
  if (timer) timer->begin(cmd, pass.name);
  context_->beginDebugLabel(cmd, pass.name);
  const PassDecl& decl = passes_[pass.pass];
  PassResources resources(*this, pass.pass);
  boundImages_.clear();  // keeps its capacity
  for (const ResourceUse& use : decl.uses)
    if (use.binding != kNoBinding)
      boundImages_.push_back({use.binding, resources.image({use.resource})});
  for (const auto& [resource, binding] : decl.placeholders)
    boundImages_.push_back({binding, resources.image({resource})});
  if (decl.record) decl.record(cmd, resources);
  context_->endDebugLabel(cmd);
  if (timer) timer->end(cmd);
}

ResolvedImage FrameGraph::resolvedImage(const std::string& name) const {
  for (uint32_t r = 0; r < resources_.size(); ++r) {
    const ResourceDecl& decl = resources_[r];
    if (decl.name != name) continue;
    if (!decl.isImage) fail("frame graph: '{}' is a buffer, not an image", name);
    if (decl.kind == ResourceKind::History)
      fail("frame graph: '{}' is a history image; resolvedImage() takes others", name);
    if (r >= resolved_.size() || r >= liveResources_.size() || !liveResources_[r] ||
        !resolved_[r].image.image)
      fail("frame graph: '{}' was not used by the last executed frame", name);
    ResolvedImage image = resolved_[r].image;
    auto state = states_.find(physicalKey(decl));
    image.layout = state == states_.end() ? VK_IMAGE_LAYOUT_UNDEFINED : state->second.layout;
    return image;
  }
  fail("frame graph: no image '{}' in the last frame ({})", name, validNames());
}

void FrameGraph::execute(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (!context_) fail("frame graph: execute() before allocate()");
  if (!compiled_) compile();
  resolveResources();
  for (const PassPlan& pass : plan_.passes) recordPass(cmd, pass, timer);
  recordBarriers(cmd, plan_.finalBarriers);
  endFrame();
}

void FrameGraph::executePassByPass(vk::GpuTimer* timer) {
  if (!context_) fail("frame graph: executePassByPass() before allocate()");
  if (!compiled_) compile();
  resolveResources();
  for (const PassPlan& pass : plan_.passes) {
    const vk::HostCost start = vk::HostCost::now();
    context_->submitAndWait([&](VkCommandBuffer cmd) { recordPass(cmd, pass, timer); });
    vk::logPassRun(pass.name, vk::HostCost::now() - start);
  }
  context_->submitAndWait([&](VkCommandBuffer cmd) { recordBarriers(cmd, plan_.finalBarriers); });
  endFrame();
}

// ---- debug views ----------------------------------------------------------------------------

void FrameGraph::recordDebugViewCopy(VkCommandBuffer cmd, const PassResources& resources,
                                     DebugViewRequest& request) {
  const ResourceDecl& target = resources_[request.target];
  ResolvedBuffer readback = resources.buffer({request.readback});
  DebugView& view = request.view;
  view = DebugView{.name = request.name,
                   .resource = target.name,
                   .isImage = target.isImage,
                   .frame = frameIndex_};
  if (target.isImage) {
    ResolvedImage image = resources.image({request.target});
    VkBufferImageCopy region{};
    VkImageAspectFlags aspect =
        isDepthFormat(image.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    region.imageSubresource = {aspect, 0, 0, image.layers};
    region.imageExtent = {image.extent.width, image.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, image.layout, readback.buffer, 1, &region);
    view.format = image.format;
    view.width = image.extent.width;
    view.height = image.extent.height;
    view.layers = image.layers;
  } else {
    ResolvedBuffer source = resources.buffer({request.target});
    VkBufferCopy region{0, 0, std::min(source.size, readback.size)};
    vkCmdCopyBuffer(cmd, source.buffer, readback.buffer, 1, &region);
  }
  request.captured = true;
}

DebugView FrameGraph::readDebugView(const std::string& name) const {
  auto request = std::find_if(debugViews_.begin(), debugViews_.end(),
                              [&](const DebugViewRequest& r) { return r.name == name; });
  if (request == debugViews_.end()) fail("debug view '{}' was not requested", name);
  if (!request->captured)
    fail("debug view '{}' has not been captured yet: execute a frame after requesting it", name);
  const vk::Buffer& readback = physical_.at("debug-view:" + name).buffer;
  DebugView view = request->view;
  size_t bytes = readback.size();
  if (view.isImage)
    bytes = size_t(view.width) * view.height * view.layers * bytesPerTexel(view.format);
  view.bytes.resize(bytes);
  std::memcpy(view.bytes.data(), readback.mapped(), bytes);
  return view;
}

// ---- what a pass's callback sees -----------------------------------------------------------

ResolvedImage PassResources::image(ImageHandle handle) const {
  const FrameGraph::PassDecl& pass = graph_.passes_[pass_];
  for (const FrameGraph::ResourceUse& use : pass.uses) {
    if (use.resource != handle.index) continue;
    if (!graph_.resources_[use.resource].isImage) break;
    ResolvedImage image = graph_.resolved_[use.resource].image;
    image.layout = use.info.layout;
    return image;
  }
  fail(
      "pass '{}' did not declare image '{}': add .read() or .write() so the graph can "
      "synchronize it",
      pass.name, graph_.resourceDecl(handle.index, "image").name);
}

ResolvedBuffer PassResources::buffer(BufferHandle handle) const {
  const FrameGraph::PassDecl& pass = graph_.passes_[pass_];
  for (const FrameGraph::ResourceUse& use : pass.uses)
    if (use.resource == handle.index && !graph_.resources_[use.resource].isImage)
      return graph_.resolved_[use.resource].buffer;
  fail(
      "pass '{}' did not declare buffer '{}': add .read() or .write() so the graph can "
      "synchronize it",
      pass.name, graph_.resourceDecl(handle.index, "buffer").name);
}

bool PassResources::historyValid(const HistoryImage& history) const {
  return graph_.historyValid(history);
}

bool PassResources::historyValid(const HistoryBuffer& history) const {
  return graph_.historyValid(history);
}

std::span<const BoundImage> PassResources::boundImages() const {
  return graph_.boundImages_;
}

const std::string& PassResources::passName() const {
  return graph_.passes_[pass_].name;
}
VkExtent2D PassResources::renderResolution() const {
  return graph_.resolution_;
}
uint64_t PassResources::frameIndex() const {
  return graph_.frameIndex_;
}

}  // namespace bounce::graph
