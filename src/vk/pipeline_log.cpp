#include "vk/pipeline_log.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <mutex>

namespace bounce::vk {

namespace {

template <typename Entry>
std::vector<Entry> slowestFirst(std::vector<Entry> entries, double (*key)(const Entry&)) {
  std::stable_sort(entries.begin(), entries.end(),
                   [key](const Entry& a, const Entry& b) { return key(a) > key(b); });
  return entries;
}

class Log {
 public:
  ~Log() {
    if (pipelineTimesRequested()) print();
  }
  uint32_t addPipeline(const std::string& name, const HostCost& cost) {
    std::lock_guard lock(mutex_);
    pipelines_.push_back({name, cost, false});
    return uint32_t(pipelines_.size() - 1);
  }
  void markUsed(uint32_t index) {
    std::lock_guard lock(mutex_);
    if (index < pipelines_.size()) pipelines_[index].used = true;
  }
  void addPass(const std::string& pass, const HostCost& cost) {
    std::lock_guard lock(mutex_);
    passes_.push_back({pass, cost});
  }
  std::vector<PipelineLogEntry> pipelines() const {
    std::lock_guard lock(mutex_);
    return pipelines_;
  }
  std::vector<PassRunEntry> passes() const {
    std::lock_guard lock(mutex_);
    return passes_;
  }

 private:
  void print() const {
    HostCost total, unused;
    std::fprintf(stderr, "pipelines created (BOUNCE_PIPELINE_TIMES), slowest first:\n");
    std::fprintf(stderr, "  %10s %10s\n", "wall ms", "cpu ms");
    for (const PipelineLogEntry& e : slowestFirst<PipelineLogEntry>(
             pipelines(), [](const PipelineLogEntry& e) { return e.created.cpuMs; })) {
      std::fprintf(stderr, "  %10.1f %10.1f  %-6s  %s\n", e.created.wallMs, e.created.cpuMs,
                   e.used ? "used" : "UNUSED", e.name.c_str());
      total = {total.wallMs + e.created.wallMs, total.cpuMs + e.created.cpuMs};
      if (!e.used) unused = {unused.wallMs + e.created.wallMs, unused.cpuMs + e.created.cpuMs};
    }
    std::fprintf(stderr, "  %10.1f %10.1f  total (unused: %.1f ms wall, %.1f ms cpu)\n",
                 total.wallMs, total.cpuMs, unused.wallMs, unused.cpuMs);
    std::vector<PassRunEntry> passes = this->passes();
    if (passes.empty()) return;
    total = {};
    std::fprintf(stderr, "first frame pass by pass (first dispatch compiles), slowest first:\n");
    for (const PassRunEntry& e :
         slowestFirst<PassRunEntry>(passes, [](const PassRunEntry& e) { return e.cost.cpuMs; })) {
      std::fprintf(stderr, "  %10.1f %10.1f  %s\n", e.cost.wallMs, e.cost.cpuMs, e.pass.c_str());
      total = {total.wallMs + e.cost.wallMs, total.cpuMs + e.cost.cpuMs};
    }
    std::fprintf(stderr, "  %10.1f %10.1f  total\n", total.wallMs, total.cpuMs);
  }

  mutable std::mutex mutex_;
  std::vector<PipelineLogEntry> pipelines_;
  std::vector<PassRunEntry> passes_;
};

Log& theLog() {
  static Log log;
  return log;
}

}  // namespace

HostCost HostCost::now() {
  using Ms = std::chrono::duration<double, std::milli>;
  return {Ms(std::chrono::steady_clock::now().time_since_epoch()).count(),
          1000.0 * double(std::clock()) / CLOCKS_PER_SEC};
}

uint32_t logPipelineCreated(const std::string& name, const HostCost& cost) {
  return theLog().addPipeline(name, cost);
}

void markPipelineUsed(uint32_t index) {
  theLog().markUsed(index);
}

void logPassRun(const std::string& pass, const HostCost& cost) {
  theLog().addPass(pass, cost);
}

std::vector<PipelineLogEntry> pipelineLog() {
  return theLog().pipelines();
}

std::vector<PassRunEntry> passRunLog() {
  return theLog().passes();
}

bool pipelineTimesRequested() {
  const char* value = std::getenv("BOUNCE_PIPELINE_TIMES");
  return value && *value && std::strcmp(value, "0") != 0;
}

}  // namespace bounce::vk
