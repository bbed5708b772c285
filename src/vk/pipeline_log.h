// What starting up costs in shader compilation, measured: every pipeline the process creates
// (name, wall time of vkCreate*Pipelines, whether anything bound it afterwards) and, where the
// frame graph ran a frame pass by pass, each pass's host wall and CPU time. On a CPU device
// (lavapipe) the LLVM compile happens at a pipeline's first dispatch, so the second table is
// where it shows (docs/startup.md). With BOUNCE_PIPELINE_TIMES=1 both are printed to stderr
// when the process exits.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace bounce::vk {

// Host time: wall and CPU (all of the process's threads; lavapipe compiles on its queue thread).
struct HostCost {
  double wallMs = 0.0;
  double cpuMs = 0.0;
  static HostCost now();  // since an arbitrary origin; subtract two
  HostCost operator-(const HostCost& o) const { return {wallMs - o.wallMs, cpuMs - o.cpuMs}; }
};

struct PipelineLogEntry {
  std::string name;   // the shader (compute) or "vertex + fragment" (graphics)
  HostCost created;   // the vkCreate*Pipelines call
  bool used = false;  // bound by a command buffer at least once
};

struct PassRunEntry {
  std::string pass;
  HostCost cost;  // recording, submitting and waiting for the pass alone
};

// Appends an entry; returns its index, for markPipelineUsed.
uint32_t logPipelineCreated(const std::string& name, const HostCost& cost);
void markPipelineUsed(uint32_t index);
void logPassRun(const std::string& pass, const HostCost& cost);

// Copies of the entries so far, in order.
std::vector<PipelineLogEntry> pipelineLog();
std::vector<PassRunEntry> passRunLog();

// Whether BOUNCE_PIPELINE_TIMES (set, not "0") asks for the tables on stderr at exit, and for the
// first frame to run pass by pass.
bool pipelineTimesRequested();

}  // namespace bounce::vk
