// A compiled frame: which passes run, in which order, and the barriers before each. Plain data
// (names and Vulkan enum values, no Vulkan objects) so tests can read it without a GPU.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "graph/access.h"
#include "graph/barrier.h"

namespace bounce::graph {

struct PlannedBarrier {
  uint32_t resource = 0;  // index of the resource declaration in this frame
  std::string resourceName;
  bool isImage = false;
  Barrier barrier;
};

struct PassPlan {
  uint32_t pass = 0;  // index of the pass declaration in this frame
  std::string name;
  QueueKind kind = QueueKind::Compute;
  std::vector<PlannedBarrier> barriers;  // recorded as one vkCmdPipelineBarrier2 before the pass

  const PlannedBarrier* barrierFor(const std::string& resource) const;
};

struct FramePlan {
  std::vector<PassPlan> passes;           // in execution order (declaration order)
  std::vector<std::string> culledPasses;  // declared, but nothing reads what they write
  // After the last pass: makes writes to mapped (readback) buffers visible to the host.
  std::vector<PlannedBarrier> finalBarriers;
  // Per physical resource (see FrameGraph::physicalKey): its state once the frame has run.
  std::vector<std::pair<std::string, ResourceState>> exitStates;

  const PassPlan* pass(const std::string& name) const;
  bool culled(const std::string& name) const;
};

}  // namespace bounce::graph
