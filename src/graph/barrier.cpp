#include "graph/barrier.h"

#include <algorithm>

namespace bounce::graph {

namespace {

bool covers(VkFlags64 have, VkFlags64 want) {
  return (have & want) == want;
}

bool alreadyVisible(const ResourceState& state, const AccessInfo& next) {
  return std::any_of(state.visibleTo.begin(), state.visibleTo.end(), [&](const StageAccess& v) {
    return covers(v.stages, next.stages) && covers(v.access, next.access);
  });
}

// A write or a layout transition: everything before it must be finished. Reads only need an
// execution dependency (WAR); a write not yet made available is flushed (WAW, and so that a
// transition does not lose it).
std::optional<Barrier> orderAfterEverything(ResourceState& state, const AccessInfo& next,
                                            bool isImage) {
  Barrier barrier;
  barrier.srcStages = state.writeStages | state.readStages;
  barrier.srcAccess = state.pendingWrites;
  barrier.dstStages = next.stages;
  barrier.dstAccess = next.access;
  barrier.oldLayout = isImage ? state.layout : VK_IMAGE_LAYOUT_UNDEFINED;
  barrier.newLayout = isImage ? next.layout : VK_IMAGE_LAYOUT_UNDEFINED;
  bool transition = isImage && state.layout != next.layout;

  if (next.writes) {
    state.writeStages = next.stages;
    state.pendingWrites = writeAccessBits(next.access);
    state.readStages = VK_PIPELINE_STAGE_2_NONE;
    state.visibleTo.clear();
  } else {
    // A read in a new layout: the transition made earlier writes visible to this read only.
    state.writeStages |= next.stages;
    state.pendingWrites = VK_ACCESS_2_NONE;
    state.readStages = next.stages;
    state.visibleTo = {{next.stages, next.access}};
  }
  if (isImage) state.layout = next.layout;

  if (!transition && barrier.srcStages == VK_PIPELINE_STAGE_2_NONE) return std::nullopt;
  return barrier;
}

// A read in the current layout: it must see the last write, once per stage/access.
std::optional<Barrier> makeWriteVisible(ResourceState& state, const AccessInfo& next,
                                        bool isImage) {
  bool written = state.writeStages != VK_PIPELINE_STAGE_2_NONE;
  bool needed = written && !alreadyVisible(state, next);
  std::optional<Barrier> barrier;
  if (needed) {
    barrier = Barrier{};
    barrier->srcStages = state.writeStages;
    barrier->srcAccess = state.pendingWrites;
    barrier->dstStages = next.stages;
    barrier->dstAccess = next.access;
    barrier->oldLayout = barrier->newLayout = isImage ? state.layout : VK_IMAGE_LAYOUT_UNDEFINED;
    state.pendingWrites = VK_ACCESS_2_NONE;
    state.visibleTo.push_back({next.stages, next.access});
  }
  state.readStages |= next.stages;
  return barrier;
}

}  // namespace

std::optional<Barrier> deriveBarrier(ResourceState& state, const AccessInfo& next, bool isImage) {
  bool transition = isImage && state.layout != next.layout;
  if (next.writes || transition) return orderAfterEverything(state, next, isImage);
  return makeWriteVisible(state, next, isImage);
}

}  // namespace bounce::graph
