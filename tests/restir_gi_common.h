// What the ReSTIR GI tests (test_restir_gi.cpp) and the restir-gi-diag tool (tools/) share: the
// configuration under which the hybrid frame is comparable with the reference pixel for pixel
// (every material Lambert, camera rays through pixel centres), the reference image, image
// comparisons, and the sun-jump run.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "frame/presets.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "tools/image_io.h"
#include "vk/context.h"

namespace bounce::test {

// Adds `image` to `sum` pixel by pixel; an empty `sum` becomes a copy of `image`.
void accumulate(ImageRGBA32F& sum, const ImageRGBA32F& image);
// `image` with its RGB multiplied by s (alpha kept).
ImageRGBA32F scaled(ImageRGBA32F image, float s);
// Rec. 709 luminance of pixel i.
double luminance(const ImageRGBA32F& image, size_t i);

struct Comparison {
  double relMse = 0.0;
  double meanRatio = 0.0;  // mean luminance of the test over the reference's
};
Comparison compare(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// The reference path tracer's view through `camera` with every material Lambert and camera rays
// through pixel centres, 16 bounces: what the composite of giSettings() estimates.
ImageRGBA32F referenceImage(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                            const Camera& camera, uint32_t width, uint32_t height, uint32_t spp,
                            uint32_t seed = 1);

// referenceImage() read from tests/data/references/ when stored there (docs/testing.md, "Stored
// references"): the long tests' references take minutes on lavapipe. A stored file is checked
// before use: its camera and options must match exactly, and a fresh render at 1/16 of its
// samples (another seed) must agree with it within that render's own noise; a mismatch throws
// bounce::Error saying how to regenerate. BOUNCE_REGENERATE_REFERENCES=1 renders and (re)writes
// the file; without a stored file it renders as referenceImage() does.
// How far a stored reference lies from a fresh render made of two independent halves a and b,
// in units of that render's own noise (about 1 when the stored image is a converged render of
// the same view; storedReferenceImage refuses it above 4).
double referenceStaleness(const ImageRGBA32F& stored, const ImageRGBA32F& a, const ImageRGBA32F& b);
std::string storedReferencePath(const Scene& scene, uint32_t width, uint32_t height, uint32_t spp);
ImageRGBA32F storedReferenceImage(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                                  const Camera& camera, uint32_t width, uint32_t height,
                                  uint32_t spp);

// The desktop preset's cache (4 candidates and 4 validation rays per cell per frame, alpha-tested
// rays) with the given ReSTIR GI settings, at a test's size with full-resolution shadows.
HybridSettings giSettings(uint32_t width, uint32_t height, const RestirGiSettings& gi);

// Prints the `count` pixels that contribute most to relMSE(test, reference) (relMSE's epsilon,
// 0.01), and relMSE without them: a few pixels whose reference is nearly black can dominate it.
void printWorstPixels(const ImageRGBA32F& test, const ImageRGBA32F& reference, size_t count);

// The sun jump on a static view: 48 frames under the scene's sun mirrored about the vertical
// axis (its lit patches elsewhere, every history full), then the sun jumps back (a lighting
// cut) for 64 frames; then a camera cut (resetHistory, a view halfway to the target) for 17
// frames. Errors are the composite's relMSE against `reference`, taken under the scene's sun.
struct SunJumpRun {
  std::string sceneName;
  double before = 0.0;              // the last frame before the jump
  std::vector<double> after;        // frames 1 .. 64 after the jump
  std::vector<std::string> stages;  // the views traced for the first frames after the jump
  std::vector<std::vector<double>> stageMeans;  // [frame - 1][stage]: mean luminance
  double firstCutLuminance = 0.0;               // mean of the first frame after the camera cut
  double settledCutLuminance = 0.0;             // ... and of the frame 16 frames later
  size_t firstCutNonFinite = 0;                 // NaN/Inf pixels in the first frame after the cut

  // The error "within 10 frames": mean of frames 8-10 (one frame's error varies by +-30 %).
  double recovered() const;
  // The error long after the jump: mean of frames 49-64.
  double converged() const;
};
// Mean luminances of `stages` (debug views, e.g. "cache", "gi.resolved") are recorded for the
// 64 frames after the jump.
SunJumpRun runSunJump(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                      const Camera& camera, const HybridSettings& settings,
                      const ImageRGBA32F& reference, const std::vector<std::string>& stages = {});
// The white furnace (the built-in `furnace`: albedo 0.5, emission 1 on every surface): radiance
// 2 everywhere, so the composite is 2 at every pixel and each GI estimate (irradiance / pi per
// unit albedo) is 2 too. Renders frames 1-48 of a static view with `settings` and averages
// frames 33-48: the composite's mean, its darkest and brightest pixel over those frames, and
// the mean of each of `stages` (debug views: "gi.reservoir-estimate", "gi.resolved", ...), so
// that a loss of energy can be traced to its stage.
struct FurnaceRun {
  int frames = 0;  // rendered; frames 33 .. frames averaged
  double mean = 0.0;
  float lowest = 0.0f, highest = 0.0f;
  std::vector<double> stageMeans;  // one per stage
};
// The chain's stages in order, for runFurnace.
inline const std::vector<std::string> kFurnaceStages = {
    "gi.candidate-estimate", "gi.reservoir-estimate",
    "gi.spatial-0-estimate", "gi.spatial-1-estimate",
    "gi.validated-estimate", "gi.patched-estimate",
    "gi.resolved",           "gi.diffuse"};
FurnaceRun runFurnace(vk::Context& context, const HybridSettings& settings,
                      const std::vector<std::string>& stages = {}, int frames = 48);
// The run on one line, with the stages' means.
void printFurnace(const char* label, const HybridSettings& settings, const FurnaceRun& run,
                  const std::vector<std::string>& stages = {});

// The run's errors on two lines: frames 1-12 and every 8th after the jump (every frame with
// `everyFrame`), each stage's mean where recorded, and the recovered and converged errors; then
// the camera cut's luminances.
void printSunJump(const SunJumpRun& run, bool everyFrame);

// The sun-jump tests' run (Evolve's, GI-1.0's and Lux's): runSunJump on `sunroom`'s own camera
// at the settings' size against its stored 2,048-spp reference, printed; `validationErrors` is
// the run's context's count.
struct SunroomSunJump {
  SunJumpRun run;
  uint32_t validationErrors = 0;
};
SunroomSunJump runSunroomSunJump(const HybridSettings& settings);

// The long animated runs (RestirGi.LongAnimatedRunStaysFinite, LuxGi.AnimatedRunStaysFinite):
// `frames` frames of `sceneName` at 30 frames a second with its scripted motion, the camera
// swaying (20 degrees, 0.3 dolly, 8 s) and the sun turning (0.5 rad/s), the Vulkan validation
// layers on. The cache casts one candidate and one validation ray per cell and frame: its
// validation path is covered at a quarter of the desktop preset's rays (its ~5,000 cells' rays,
// not a small view's pixels, set these tests' time on lavapipe).
struct AnimatedRun {
  size_t nonFinite = 0;  // NaN/Inf pixels of the `views`, read every 8th frame
  uint32_t validationErrors = 0;
};
AnimatedRun runAnimated(const std::string& sceneName, HybridSettings settings, int frames,
                        const std::vector<std::string>& views);

}  // namespace bounce::test
