// Compiling a declared frame (CPU only): debug-view copies are added, declarations validated,
// passes nobody needs culled, and the barriers before each pass derived from the state every
// resource was left in (by earlier passes, or by last frame).
#include <algorithm>

#include "core/error.h"
#include "graph/frame_graph.h"

namespace bounce::graph {

namespace {

bool readsContents(const AccessInfo& info, Access access) {
  return !info.writes || access == Access::StorageReadWrite;
}

}  // namespace

const FramePlan& FrameGraph::compile() {
  removeInternalDeclarations();
  addDebugViewPasses();
  std::vector<uint32_t> order = executionOrder();
  validate(order);
  std::vector<bool> live = findLivePasses(order);
  deriveBarriers(order, live);
  collectUsage(live);
  compiled_ = true;
  return plan_;
}

void FrameGraph::removeInternalDeclarations() {
  resources_.erase(resources_.begin() + ptrdiff_t(declaredResources_), resources_.end());
  passes_.erase(passes_.begin() + ptrdiff_t(declaredPasses_), passes_.end());
  compiled_ = false;
}

// ---- debug views ----------------------------------------------------------------------------

std::vector<std::string> FrameGraph::declaredPassNames() const {
  std::vector<std::string> names;
  for (size_t i = 0; i < declaredPasses_; ++i) names.push_back(passes_[i].name);
  return names;
}

std::vector<std::string> FrameGraph::declaredResourceNames() const {
  std::vector<std::string> names;
  for (size_t i = 0; i < declaredResources_; ++i) names.push_back(resources_[i].name);
  return names;
}

std::string FrameGraph::validNames() const {
  std::string passes, resources;
  for (size_t i = 0; i < declaredPasses_; ++i)
    passes += (passes.empty() ? "" : ", ") + passes_[i].name;
  for (size_t i = 0; i < declaredResources_; ++i)
    resources += (resources.empty() ? "" : ", ") + resources_[i].name;
  return fmt::format("passes: {}; resources: {}", passes.empty() ? "(none)" : passes,
                     resources.empty() ? "(none)" : resources);
}

void FrameGraph::requestDebugView(const std::string& passOrResource) {
  for (const DebugViewRequest& r : debugViews_)
    if (r.name == passOrResource) return;
  debugViews_.push_back({.name = passOrResource});
  compiled_ = false;
}

void FrameGraph::clearDebugViews() {
  debugViews_.clear();
  compiled_ = false;
}

// A pass shows the first image it writes, else the first buffer.
uint32_t FrameGraph::debugViewTarget(const std::string& name) const {
  for (size_t p = 0; p < declaredPasses_; ++p) {
    if (passes_[p].name != name) continue;
    for (bool wantImage : {true, false})
      for (const ResourceUse& use : passes_[p].uses)
        if (use.info.writes && resources_[use.resource].isImage == wantImage) return use.resource;
    fail("debug view '{}': the pass writes nothing to show", name);
  }
  for (size_t r = 0; r < declaredResources_; ++r)
    if (resources_[r].name == name) return uint32_t(r);
  fail("debug view '{}': no pass or resource has that name ({})", name, validNames());
}

// The readback buffer follows the resolution when its target does.
BufferDesc FrameGraph::readbackDesc(const ResourceDecl& target) const {
  BufferDesc desc{.memory = vk::MemoryUse::Readback};
  if (!target.isImage) {
    desc.size = target.buffer.size;
    return desc;
  }
  uint32_t texel = bytesPerTexel(target.image.format);
  if (texel == 0)
    fail("debug view of '{}': its format (VkFormat {}) cannot be read back", target.name,
         int(target.image.format));
  VkDeviceSize perPixel = VkDeviceSize(texel) * target.image.layers;
  const ImageSize& size = target.image.size;
  desc.size = size.followsResolution() ? BufferSize::perPixel(perPixel, size.divisor)
                                       : BufferSize::fixed(perPixel * size.width * size.height);
  return desc;
}

// Each view gets a readback buffer and a copy pass, placed right after the pass it shows (so a
// later pass overwriting the image does not hide its output) or at the end for a resource.
void FrameGraph::addDebugViewPasses() {
  for (size_t i = 0; i < debugViews_.size(); ++i) {
    try {
      addDebugViewPass(debugViews_[i]);
    } catch (const Error&) {
      debugViews_.erase(debugViews_.begin() + ptrdiff_t(i));  // or every later frame fails too
      throw;
    }
  }
}

void FrameGraph::addDebugViewPass(DebugViewRequest& request) {
  request.target = debugViewTarget(request.name);
  const ResourceDecl& target = resources_[request.target];
  ResourceDecl readback{.name = "debug-view:" + request.name,
                        .kind = ResourceKind::Persistent,
                        .buffer = readbackDesc(target)};
  readback.group = readback.name;
  resources_.push_back(std::move(readback));
  request.readback = uint32_t(resources_.size() - 1);

  PassDecl copy{.name = "debug-view:" + request.name, .sideEffects = true};
  copy.uses = {
      {request.target, Access::TransferSrc, accessInfo(Access::TransferSrc, QueueKind::Compute)},
      {request.readback, Access::TransferDst, accessInfo(Access::TransferDst, QueueKind::Compute)}};
  for (size_t p = 0; p < declaredPasses_; ++p)
    if (passes_[p].name == request.name) copy.runsAfter = uint32_t(p);
  std::string name = request.name;
  copy.record = [this, name](VkCommandBuffer cmd, const PassResources& resources) {
    for (DebugViewRequest& r : debugViews_)
      if (r.name == name) recordDebugViewCopy(cmd, resources, r);
  };
  passes_.push_back(std::move(copy));
}

// Declaration order; debug-view copies right after the pass they show, or last.
std::vector<uint32_t> FrameGraph::executionOrder() const {
  std::vector<uint32_t> order;
  auto addCopiesAfter = [&](uint32_t shown) {
    for (size_t p = declaredPasses_; p < passes_.size(); ++p)
      if (passes_[p].runsAfter == shown) order.push_back(uint32_t(p));
  };
  for (uint32_t p = 0; p < declaredPasses_; ++p) {
    order.push_back(p);
    addCopiesAfter(p);
  }
  addCopiesAfter(kNoResource);
  return order;
}

// ---- validation -----------------------------------------------------------------------------

void FrameGraph::validate(const std::vector<uint32_t>& order) const {
  std::vector<bool> written(resources_.size(), false);
  for (uint32_t p : order) {
    for (const ResourceUse& use : passes_[p].uses) {
      const ResourceDecl& r = resources_[use.resource];
      if (r.kind == ResourceKind::Transient && !written[use.resource] &&
          readsContents(use.info, use.access)) {
        auto later = std::find_if(order.begin(), order.end(), [&](uint32_t q) {
          return std::any_of(passes_[q].uses.begin(), passes_[q].uses.end(),
                             [&](auto& u) { return u.resource == use.resource && u.info.writes; });
        });
        fail("pass '{}' reads transient '{}' before any pass writes it this frame{}",
             passes_[p].name, r.name,
             later == order.end()
                 ? std::string(" (no pass writes it)")
                 : fmt::format(" (first written by '{}', declared later)", passes_[*later].name));
      }
      if (use.info.writes) written[use.resource] = true;
    }
  }
  for (uint32_t r = 0; r < resources_.size(); ++r)
    if (resources_[r].role == HistoryRole::Current && !written[r])
      fail(
          "history '{}': no pass writes it this frame, so next frame's '{}.previous' would be "
          "stale",
          resources_[r].name, resources_[r].name);
}

// ---- culling --------------------------------------------------------------------------------

// Walks the passes backwards: a pass is live when it has side effects, writes something that
// outlives the frame (persistent, history, imported), or writes something a later live pass
// reads. A pure overwrite (StorageWrite, TransferDst) ends the interest in earlier writers.
std::vector<bool> FrameGraph::findLivePasses(const std::vector<uint32_t>& order) const {
  std::vector<bool> live(passes_.size(), false);
  std::vector<bool> needed(resources_.size(), false);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const PassDecl& pass = passes_[*it];
    bool keep = pass.sideEffects;
    for (const ResourceUse& use : pass.uses) {
      const ResourceDecl& r = resources_[use.resource];
      if (use.info.writes && (r.kind != ResourceKind::Transient || needed[use.resource]))
        keep = true;
      if (use.access == Access::HostRead) keep = true;
    }
    if (!keep) continue;
    live[*it] = true;
    // What it reads, or only partly overwrites (attachments, read-modify-write), needs the
    // earlier writers; what it overwrites entirely does not.
    for (const ResourceUse& use : pass.uses)
      needed[use.resource] = !use.info.writes || use.info.keepsContents;
  }
  return live;
}

// ---- barriers -------------------------------------------------------------------------------

// Where a resource starts this frame: where last frame left it. A transient's contents are
// dropped (UNDEFINED layout) but last frame's accesses still have to finish before it is reused.
ResourceState FrameGraph::entryState(const ResourceDecl& resource) const {
  std::string key = physicalKey(resource);
  auto state = states_.find(key);
  if (resource.kind == ResourceKind::Imported && resource.isImage &&
      resource.importedImage.externalWrites)
    return ResourceState{.layout = resource.importedImage.layout,
                         .writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                         .pendingWrites = VK_ACCESS_2_MEMORY_WRITE_BIT};
  if (resource.kind == ResourceKind::Imported) {
    auto handle = importedHandles_.find(key);
    uint64_t current = resource.isImage ? uint64_t(resource.importedImage.image)
                                        : uint64_t(resource.importedBuffer.buffer);
    if (state == states_.end() || handle == importedHandles_.end() || handle->second != current)
      return ResourceState{.layout = resource.importedImage.layout};
  }
  ResourceState entry = state == states_.end() ? ResourceState{} : state->second;
  if (resource.kind == ResourceKind::Transient) {
    entry.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    entry.visibleTo.clear();
  }
  return entry;
}

bool FrameGraph::hostVisible(const ResourceDecl& resource) const {
  return !resource.isImage && resource.buffer.memory == vk::MemoryUse::Readback;
}

void FrameGraph::deriveBarriers(const std::vector<uint32_t>& order, const std::vector<bool>& live) {
  plan_ = FramePlan{};
  std::vector<ResourceState> states;
  for (const ResourceDecl& r : resources_) states.push_back(entryState(r));
  liveResources_.assign(resources_.size(), false);

  for (uint32_t p : order) {
    const PassDecl& pass = passes_[p];
    if (!live[p]) {
      plan_.culledPasses.push_back(pass.name);
      continue;
    }
    PassPlan planned{.pass = p, .name = pass.name, .kind = pass.kind};
    for (const ResourceUse& use : pass.uses) {
      const ResourceDecl& r = resources_[use.resource];
      liveResources_[use.resource] = true;
      if (auto barrier = deriveBarrier(states[use.resource], use.info, r.isImage))
        planned.barriers.push_back({use.resource, r.name, r.isImage, *barrier});
    }
    plan_.passes.push_back(std::move(planned));
  }

  AccessInfo hostRead = accessInfo(Access::HostRead, QueueKind::Compute);
  for (uint32_t r = 0; r < resources_.size(); ++r) {
    if (!liveResources_[r]) continue;
    if (hostVisible(resources_[r]))
      if (auto barrier = deriveBarrier(states[r], hostRead, false))
        plan_.finalBarriers.push_back({r, resources_[r].name, false, *barrier});
    plan_.exitStates.emplace_back(physicalKey(resources_[r]), states[r]);
  }
}

// Usage flags follow from the accesses; both sides of a history get the union, as they swap.
void FrameGraph::collectUsage(const std::vector<bool>& livePasses) {
  usage_.assign(resources_.size(), 0);
  for (size_t p = 0; p < passes_.size(); ++p) {
    if (!livePasses[p]) continue;
    for (const ResourceUse& use : passes_[p].uses) {
      const bool image = resources_[use.resource].isImage;
      usage_[use.resource] |= image ? imageUsageFor(use.access) : bufferUsageFor(use.access);
      for (Access merged : use.mergedReads)
        usage_[use.resource] |= image ? imageUsageFor(merged) : bufferUsageFor(merged);
    }
  }
  for (uint32_t a = 0; a < resources_.size(); ++a)
    for (uint32_t b = 0; b < resources_.size(); ++b)
      if (a != b && resources_[a].kind == ResourceKind::History &&
          resources_[a].group == resources_[b].group)
        usage_[a] |= usage_[b];
}

// ---- the end of a frame ---------------------------------------------------------------------

void FrameGraph::endFrame() {
  if (!compiled_) compile();
  for (auto& [key, state] : plan_.exitStates) states_[key] = state;
  for (uint32_t r = 0; r < resources_.size(); ++r) {
    const ResourceDecl& decl = resources_[r];
    if (decl.kind == ResourceKind::Imported && liveResources_[r])
      importedHandles_[physicalKey(decl)] =
          decl.isImage ? uint64_t(decl.importedImage.image) : uint64_t(decl.importedBuffer.buffer);
  }
  for (const ResourceDecl& decl : resources_) {
    if (decl.role != HistoryRole::Current) continue;
    HistoryInfo& info = history_[decl.group];
    info.parity ^= 1u;
    info.valid = true;
  }
  ++frameIndex_;
  compiled_ = false;
}

}  // namespace bounce::graph
