// Pass "primary-view": ray-cast primary visibility shaded with one surface attribute (albedo,
// normal, depth, instance or geometry id), the first image of a loaded scene.
#pragma once
#include <optional>
#include <string>

#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "shared/camera.h"
#include "tools/image_io.h"
#include "vk/gpu_timer.h"
#include "vk/pipeline.h"

namespace bounce {

enum class PrimaryViewKind { Albedo, Normal, Depth, Instance, Geometry };

// "primary-albedo" -> Albedo, ...; nullopt for other names.
std::optional<PrimaryViewKind> primaryViewFromName(const std::string& name);
const char* primaryViewNames();  // for help and error text

// Camera constants for a W x H image; near/far depth for the depth view from the scene bounds.
gpu::GpuCamera makeGpuCamera(const Camera& camera, uint32_t width, uint32_t height,
                             const Aabb& sceneBounds);

class PrimaryViewPass {
 public:
  PrimaryViewPass(vk::Context& context, const GpuScene& scene);
  // Renders and reads back the view (linear RGB, black where the primary ray misses).
  ImageRGBA32F render(const Camera& camera, uint32_t width, uint32_t height, PrimaryViewKind view,
                      vk::GpuTimer* timer = nullptr);

 private:
  vk::Context& context_;
  const GpuScene& scene_;
  vk::ComputePipeline pipeline_;
};

}  // namespace bounce
