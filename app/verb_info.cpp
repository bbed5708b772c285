// bounce info: the Vulkan devices, which one Bounce picks, and the capabilities it relies on.
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "verbs.h"
#include "vk/context.h"

namespace bounce::app {

namespace {

struct InfoOptions {
  bool json = false;
};

std::string versionString(uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                     VK_API_VERSION_PATCH(v));
}

nlohmann::json deviceJson(const vk::DeviceInfo& d, bool chosen) {
  return {{"index", d.index},
          {"name", d.name},
          {"type", d.type},
          {"driver", d.driver},
          {"api_version", versionString(d.apiVersion)},
          {"suitable", d.suitable},
          {"unsuitable_because", d.unsuitableBecause},
          {"chosen", chosen},
          {"subgroup_size", d.subgroupSize},
          {"max_storage_buffer_range", d.maxStorageBufferRange},
          {"max_push_constants_size", d.maxPushConstantsSize},
          {"max_compute_workgroup_invocations", d.maxComputeWorkGroupInvocations},
          {"device_local_bytes", d.deviceLocalBytes},
          {"timestamp_period_ns", d.timestampPeriodNs},
          {"timestamps", d.timestampsOnComputeQueue},
          {"shader_float16", d.shaderFloat16},
          {"ray_tracing_pipeline", d.rayTracingPipeline},
          {"ray_query", d.rayQuery},
          {"cooperative_matrix", d.cooperativeMatrix}};
}

void printDevice(const vk::DeviceInfo& d, bool chosen) {
  std::printf("%s [%u] %s (%s, Vulkan %s, %s)\n", chosen ? "*" : " ", d.index, d.name.c_str(),
              d.type.c_str(), versionString(d.apiVersion).c_str(), d.driver.c_str());
  if (!d.suitable) {
    std::printf("      unsupported: %s\n", d.unsuitableBecause.c_str());
    return;
  }
  std::printf(
      "      subgroup %u, max storage buffer %.0f MiB, push constants %u B, "
      "device-local %.1f GiB\n",
      d.subgroupSize, double(d.maxStorageBufferRange) / (1 << 20), d.maxPushConstantsSize,
      double(d.deviceLocalBytes) / double(1u << 30));
  std::printf(
      "      timestamps %s, float16 %s; optional: ray-tracing pipeline %s, ray query %s, "
      "cooperative matrix %s\n",
      d.timestampsOnComputeQueue ? "yes" : "no", d.shaderFloat16 ? "yes" : "no",
      d.rayTracingPipeline ? "yes" : "no", d.rayQuery ? "yes" : "no",
      d.cooperativeMatrix ? "yes" : "no");
}

int runInfo(const InfoOptions& options) {
  std::vector<vk::DeviceInfo> devices = vk::Context::listDevices();
  // The device Bounce would choose, by the same rule the renderer uses.
  vk::Context context(vk::contextOptionsFromEnvironment());
  uint32_t chosen = context.info().index;
  if (options.json) {
    nlohmann::json out = {{"devices", nlohmann::json::array()}, {"chosen", chosen}};
    for (const vk::DeviceInfo& d : devices)
      out["devices"].push_back(deviceJson(d, d.index == chosen));
    std::printf("%s\n", out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  } else {
    std::printf("Vulkan devices (* = chosen; --device N or BOUNCE_DEVICE=N to choose):\n");
    for (const vk::DeviceInfo& d : devices) printDevice(d, d.index == chosen);
    std::printf(
        "Required: Vulkan 1.3, bufferDeviceAddress, scalarBlockLayout, shaderInt64, "
        "synchronization2, dynamicRendering, timelineSemaphore\n");
  }
  return context.validationErrorCount() == 0 ? 0 : 4;
}

}  // namespace

void addInfoVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd =
      app.add_subcommand("info", "List Vulkan devices and the capabilities Bounce uses");
  cmd->add_flag("--json", options->json, "Print JSON for machines");
  cmd->callback([&action, options] { action = [options] { return runInfo(*options); }; });
}

}  // namespace bounce::app
