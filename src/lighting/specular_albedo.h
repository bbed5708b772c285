// The split-sum directional-albedo table of the glTF BRDF (shaders/shared/specular_albedo_io.h):
// per (n.v, roughness), what the specular lobe reflects of uniform light as F0 scale + bias,
// and what the diffuse lobe loses to Fresnel. `composite` weights indirect light with it
// (shaders/lighting/specular_albedo.glsl).
//
// Precomputed rather than an analytic fit: the published fits (Karis 2014's mobile
// EnvBRDFApprox, Lazarov 2013) were fitted to other BRDF variants (separable Smith, Schlick-GGX
// k) and miss ours by several percent at some roughness, more than the 2% the specular furnace
// allows. The table is made on the GPU from the very functions the reference path tracer calls
// (shaders/common/brdf.glsl), once, when the frame is created: 32 x 32 entries, 1,024
// stratified samples each, about a millisecond on a GPU and well under a second on lavapipe.
#pragma once
#include "vk/resources.h"

namespace bounce {

class SpecularAlbedoTable {
 public:
  explicit SpecularAlbedoTable(vk::Context& context);

  // vec4[SPECULAR_ALBEDO_SIZE^2] (shared/specular_albedo_io.h), read-only after construction.
  VkDeviceAddress address() const { return table_.address(); }
  const vk::Buffer& buffer() const { return table_; }

 private:
  vk::Buffer table_;
};

}  // namespace bounce
