// `di-spatial` (shaders/di/di_spatial.comp): each reservoir merged with those of 1-3 similar
// neighbours within DiSettings::spatialRadius pixels, with bias correction (ray-traced with
// DiSettings::unbiased). Not fed back.
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiSpatialPass {
 public:
  // `tracedCorrection`: whether DiConstants::flags has DI_FLAG_UNBIASED (the ray-traced bias
  // correction; DI_SPEC_SPATIAL_TRACED_CORRECTION).
  DiSpatialPass(vk::Context& context, const GpuScene& scene, bool tracedCorrection);
  // di.spatial: the reservoirs after spatial reuse.
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f,
                             graph::ImageHandle reservoirs);

 private:
  DiPass pass_;
};

}  // namespace bounce
