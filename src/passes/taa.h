// `taa` (issue 21 item 6; docs/frame.md#temporal-anti-aliasing): temporal anti-aliasing after
// `composite`. The frame shifts its primary visibility by a sub-pixel jitter (taaJitter, in
// FrameConstants::jitter: the vbuffer's rays and raster matrix, and every pass that rebuilds a
// position from a pixel); gbuffer.velocity stays the surface's unjittered motion, so the GI,
// ReSTIR and the denoisers reproject as without jitter. `taa` reprojects its history with the
// velocity, clips it to the current neighbourhood in a perceptual space and blends
// (shaders/passes/taa.comp). Its output, taa.color (the view `taa`), is what tonemap reads.
#pragma once
#include <optional>

#include <glm/glm.hpp>

#include "graph/frame_graph.h"
#include "passes/auto_exposure.h"
#include "passes/composite.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "shared/taa_io.h"

namespace bounce {

// The anti-aliasing's knobs (docs/frame.md#temporal-anti-aliasing has the measurements).
struct TaaSettings {
  // Off (the default of the struct, so a library frame and the tests take one sample at each
  // pixel centre unless they ask; `bounce render` turns it on, `--no-taa` off): no jitter, no
  // `taa` pass, tonemap reads composite.hdr.
  bool enabled = false;
  // Frames of the Halton (2, 3) jitter sequence before it repeats. 8 (as Unreal's default):
  // an exponential history of weight 0.1 weighs its last 8 frames within 2x of each other, so
  // they cover the pixel evenly; longer sequences spread their points over frames the history
  // has mostly forgotten. 1 to 1024 (1: a fixed offset, no anti-aliasing).
  uint32_t jitterPhases = 8;
  // Weight of the current frame once the history is 1 / blend frames long (before that, the
  // frames are averaged uniformly): lower is smoother and converges slower. Karis 2014 and
  // Unreal use about 0.04-0.1. (0, 1].
  float blend = 0.1f;
  // Half-width of the variance clip box in standard deviations of the 3x3 neighbourhood
  // (Salvi 2016 uses about 1): wider keeps more history through noise, narrower ghosts less.
  // > 0.
  float clipSigma = 1.0f;
};

// Throws bounce::Error naming the field when a setting is out of its range above.
void validate(const TaaSettings& settings);

// The sub-pixel offset of frame `frame` of a sequence of `phases` frames: Halton (2, 3) points
// 1 .. phases minus (0.5, 0.5), in [-0.5, 0.5) pixels. Point 0, (0, 0), is skipped: it sits on
// the pixel's corner, the corner its neighbours' last point also reaches.
glm::vec2 taaJitter(uint64_t frame, uint32_t phases);

// The world-to-clip matrix `viewProjection` shifted by `jitter` pixels of a `resolution` image
// the other way: a point seen by the ray through pixel position s + jitter lands on s, so the
// raster pass samples what the jittered rays see.
glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 jitter,
                                 glm::uvec2 resolution);

class TaaPass {
 public:
  TaaPass(vk::Context& context, const GpuScene& scene, const TaaSettings& settings);
  // The anti-aliased `hdr` (taa.color, a history image): what tonemap reads instead.
  HdrImage declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                   const HdrImage& hdr, const std::optional<Exposure>& exposure);

 private:
  TaaSettings settings_;
  ComputePass pass_;
};

}  // namespace bounce
