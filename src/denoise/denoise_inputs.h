// What the library denoisers (svgf, reblur, hybrid; docs/denoise.md) filter and the surface it
// lies on, all at render resolution: the same contract for each, none of it specific to a GI
// technique (shared/svgf_io.h and shared/reblur_io.h have the formats and encodings).
#pragma once
#include <optional>

#include "graph/frame_graph.h"

namespace bounce {

struct DenoiseInputs {
  graph::ImageHandle noisy;    // RGBA16F: the signal (rgb)
  graph::ImageHandle depth;    // R32F: linear view depth, <= 0 or non-finite: no surface
  graph::ImageHandle normals;  // RGBA16F: world normal xyz, or octahedral xy (below)
  graph::ImageHandle motion;   // RG16F: pixels moved since last frame
  // RGBA16F: where given, the signal is demodulated by it and remodulated at the end (so the
  // filter blurs irradiance, not texture); absent when the signal is already demodulated (as
  // Bounce's gi.diffuse is: radiance per unit albedo).
  std::optional<graph::ImageHandle> albedo;
  bool octahedralNormals = false;  // Bounce's gbuffer.normals: xy octahedral shading normal
  bool dropHistory = false;        // this frame starts afresh (a cut)
};

}  // namespace bounce
