// Automatic exposure (issue 18; docs/frame.md#automatic-exposure): the exposure that `tonemap`
// applies, metered from each frame's HDR image and adapted over frames as engines and eyes do,
// so that any scene shows whatever its light, a Cornell box under its one lamp or a street at
// night. Three passes (shaders/passes/exposure_*.comp, shared/auto_exposure_io.h):
//
//   exposure-histogram  composite.hdr -> exposure.histogram: pixels per quarter stop of
//                       luminance (NaN, Inf and black pixels left out)
//   exposure-adapt      exposure.histogram, exposure.state.previous -> exposure.state: the
//                       metered level, the adapted level and the exposure (clears the histogram)
//   exposure-debug      exposure.state -> `exposure`, the histogram as an image (culled unless
//                       viewed)
//
// The state stays on the GPU (a history buffer): nothing is read back on the frame's path. The
// first frame, and the first after a history reset (a camera cut, a resize), take the metered
// exposure directly, so a one-frame render is exposed right.
#pragma once
#include "graph/frame_graph.h"
#include "passes/composite.h"
#include "passes/image_pass.h"
#include "shared/auto_exposure_io.h"

namespace bounce {

// How the exposure is metered and how fast it follows. The defaults follow histogram metering
// in engines (Unreal's "Auto Exposure Histogram"); docs/frame.md#automatic-exposure shows what
// they do to the built-in scenes. Both presets use the defaults. Luminance is Rec. 709 Y of the
// composite's radiance (W/(m^2 sr)); "level" below means its log2.
struct AutoExposureSettings {
  // The metering window, as fractions of the counted pixels (finite, above 0) sorted from dark
  // to bright: the darkest `lowPercentile` and the brightest 1 - `highPercentile` are left out
  // and the mean level of the pixels between is the scene's level. Leaving out the dark half
  // exposes for what is lit (a room lit by a sun patch, not its dark corners); leaving out the
  // top 5% keeps a lamp, the sun's disc or a specular highlight from darkening the rest.
  // 0 <= low < high <= 1.
  float lowPercentile = 0.5f;
  float highPercentile = 0.95f;
  // The exposed luminance the metered level is mapped to: 0.18, photography's middle grey
  // (the reflectance an average scene is assumed to have; the ACES curve of tonemap shows it as
  // 0.27 linear, 0.55 sRGB). Must be > 0.
  float key = 0.18f;
  // The metered level is clamped to [minLog2Luminance, maxLog2Luminance] before it is adapted
  // to: scenes darker than 2^-10 (about 0.001, a moonless night sky) are shown darker rather
  // than lifted to middle grey, and an all-black frame gets the finite exposure key * 2^10 (and
  // its compensation). The top, 2^12, is far above daylight (a white wall in a 100 W/m^2 sun
  // has luminance 25, 2^4.6). Both within the histogram's [-16, 16]; min < max.
  float minLog2Luminance = -10.0f;
  float maxLog2Luminance = 12.0f;
  // Time constants of the exponential adaptation, in seconds of frame time: each frame the
  // adapted level covers 1 - exp(-dt / tau) of its distance to the metered one, so after
  // n tau it is within e^-n of the jump (a jump of 4 stops is within 5% of the exposure,
  // 0.07 stop, after 4.0 tau). The eye and engines adapt to brightness faster than to dark
  // (Unreal's default speeds 3 and 1 per second). 0 = no adaptation: every frame takes the
  // metered exposure. >= 0.
  float brighteningSeconds = 0.33f;  // the scene got brighter: the exposure falls
  float darkeningSeconds = 1.0f;     // the scene got darker: the exposure rises
};

// Throws bounce::Error naming the field when a setting is out of the range given above.
void validate(const AutoExposureSettings& settings);

// What tonemap reads.
struct Exposure {
  graph::BufferHandle state;  // exposure.state (this frame's): gpu::ExposureState
};

class AutoExposure {
 public:
  AutoExposure(vk::Context& context, const GpuScene& scene, const AutoExposureSettings& settings);

  // This frame's exposure of `hdr`, `compensationStops` brighter (the frame's exposureStops),
  // adapted over `deltaSeconds` since the last frame.
  Exposure declare(graph::FrameGraph& graph, const HdrImage& hdr, float compensationStops,
                   float deltaSeconds);

  const AutoExposureSettings& settings() const { return settings_; }

 private:
  void declareHistogram(graph::FrameGraph& graph, const HdrImage& hdr,
                        graph::BufferHandle histogram);
  void declareAdapt(graph::FrameGraph& graph, graph::BufferHandle histogram,
                    const graph::HistoryBuffer& state, gpu::ExposureAdaptConstants constants);
  void declareDebugView(graph::FrameGraph& graph, graph::BufferHandle state);

  AutoExposureSettings settings_;
  ComputePass histogram_;
  ComputePass adapt_;
  ComputePass debugView_;
};

}  // namespace bounce
