// What the library denoisers' tests (test_svgf.cpp, test_reblur.cpp) share: a denoiser on a frame
// graph of its own fed from the CPU, the noisy inputs of known mean (two planes with exponential
// noise; the GI signal of a scene at 1 frame), and issue 21's gates on the output (mean kept,
// variance lower, depth edges kept; docs/denoise.md).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "denoise/denoise_inputs.h"
#include "denoise/denoise_upload.h"
#include "graph/frame_graph.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "tools/image_io.h"
#include "vk/context.h"

namespace bounce::test {

// Rec. 709 luminance of an RGB(A) value.
double luminance(const glm::vec4& c);

// Image bytes for vk::uploadImage: fp32 values (fp16: halfBytes, denoise/denoise_upload.h).
std::vector<uint8_t> floatBytes(std::span<const float> values);
std::vector<float> flatten(const std::vector<glm::vec4>& pixels);
std::vector<glm::vec4> pixelsOf(const ImageRGBA32F& image);

// What the caller of a denoiser has per frame, on the CPU.
struct DenoiseFrame {
  std::vector<glm::vec4> noisy;    // rgb signal
  std::vector<float> depth;        // view depth, 0: none
  std::vector<glm::vec4> normals;  // xyz world normal
  std::vector<glm::vec2> motion;   // pixels moved since last frame
};

// The frame graph, the input images and the scene a denoiser's passes bind (the denoisers read
// none; ComputePass binds one at set 0: `cornell`). A test's harness holds one of these and its
// denoiser, which it builds with gpuScene().
class DenoiseRig {
 public:
  DenoiseRig(vk::Context& context, uint32_t width, uint32_t height);

  GpuScene& gpuScene() { return gpuScene_; }
  VkExtent2D extent() const { return {width_, height_}; }

  // Adds the denoiser's passes, reading `inputs`, writing `output` (RGBA16F).
  using Declare = std::function<void(graph::FrameGraph& graph, const DenoiseInputs& inputs,
                                     graph::ImageHandle output)>;
  // One frame: uploads `f`, declares, runs; returns the output.
  std::vector<glm::vec4> frame(const DenoiseFrame& f, const Declare& declare);

  // For a frame of the test's own making: begins it with `view` (the image run() returns)
  // requested, imports `image` (uploaded again between frames) and runs what was declared.
  graph::FrameGraph& beginFrame(const std::string& view);
  // Another image of the graph kept for view() after each frame (a debug view).
  void requestView(const std::string& name) { views_.push_back(name); }
  std::vector<glm::vec4> view(const std::string& name);
  graph::ImageHandle import(const std::string& name, vk::Image& image);
  std::vector<glm::vec4> run(const std::string& view);

 private:
  vk::Context& context_;
  Scene scene_;
  GpuScene gpuScene_;
  uint32_t width_, height_;
  vk::Image noisy_, depth_, normals_, motion_;
  std::vector<std::string> views_;
  graph::FrameGraph graph_;  // after what it imports: destroyed first
};

// ---- statistics against a known mean ----------------------------------------------------------

struct Gates {
  double meanIn = 0, meanOut = 0, meanTrue = 0;  // image means (luminance)
  // The image mean of the inputs the denoiser was given, weighted as its temporal stage weighs
  // them (weightedMean): what it was given to average, apart from the inputs' own noise.
  double meanSeen = 0;
  double varianceIn = 0, varianceOut = 0;  // mean squared error against the known mean
  double edgeError = 0, restError = 0;     // mean |out - mean| beside depth edges / elsewhere
  size_t edgePixels = 0, nonFinite = 0;
};

// Pixels with a surface whose 4-neighbour has a surface more than 10 % nearer or farther.
std::vector<bool> besideDepthEdge(const std::vector<float>& depth, uint32_t w, uint32_t h);

// The gates of the last frame's output against `truth`, over the pixels with a surface
// (meanSeen left 0).
Gates measure(const std::vector<glm::vec4>& noisy, const std::vector<glm::vec4>& denoised,
              const std::vector<glm::vec4>& truth, const std::vector<float>& depth, uint32_t w,
              uint32_t h);

// The image mean of `frames` weighted as a running mean with weight max(alpha, 1 / n) for the
// n-th frame (svgf-temporal's on a static view); alpha 0: the plain mean (ReBLUR's 1 / n).
double weightedMean(const std::vector<std::vector<glm::vec4>>& frames,
                    const std::vector<float>& depth, float alpha);

void print(const std::string& what, const Gates& g);

// Issue 21's three gates. `known`: the mean is compared with the known mean (exact for the
// synthetic inputs); else with the mean of the inputs the denoiser saw, since a mean estimated
// from 32 heavy-tailed frames is itself too noisy (sunroom: the plain mean of the 16 frames
// differs from that of the 32 others by 13 %).
void expectMeanKept(const Gates& g, bool known);
void expectVarianceLower(const Gates& g);
void expectEdgesKept(const Gates& g);

// Writes the images side by side, 4x, as <tempDir(tag)>/<name>.png (the directory is emptied
// once per process and tag).
void writeStrip(const std::string& tag, const std::string& name, uint32_t w, uint32_t h,
                const std::vector<std::vector<glm::vec4>>& images);

// One denoised frame of a test's harness.
using DenoiseStep = std::function<std::vector<glm::vec4>(const DenoiseFrame& f)>;

// ---- two planes of known mean ----------------------------------------------------------------

// Two planes facing the camera at depths 2 and 6 (a depth edge down the middle), means 1 and
// 0.25, each pixel's value the mean times an exponential variate (mean 1, variance 1) per frame,
// 64x48, 16 frames. `shift`: the planes move right by this many pixels a frame (motion =
// (shift, 0) everywhere; what enters at the left edge has no history), so the history must be
// reprojected to be kept. meanSeen weighted with `alpha` (weightedMean). Writes the strip
// noisy | denoised | mean as <tag>/<name>.
Gates twoPlanesGates(const DenoiseStep& denoise, float alpha, int shift, const std::string& tag,
                     const std::string& name);
constexpr uint32_t kTwoPlanesWidth = 64, kTwoPlanesHeight = 48;

// ---- a scene's GI at 1 frame -------------------------------------------------------------------

// The GI signal of the hybrid frame (Evolve, no denoiser, desktop preset, Lambert) at 1 frame:
// each frame after a history reset is an independent sample of it.
struct GiSamples {
  uint32_t width = 0, height = 0;
  DenoiseFrame surface;  // depth, normals (decoded), zero motion
  std::vector<std::vector<glm::vec4>> frames;
};
GiSamples giSamples(vk::Context& context, const std::string& sceneName, uint32_t w, uint32_t h,
                    int count);

// The gates on GI samples: the mean of the first 32 frames is the truth, the 16 after them are
// denoised in order; meanSeen weighted with `alpha`. Writes noisy | denoised | truth as
// <tag>/<name>.
constexpr int kGiMeanFrames = 32, kGiDenoisedFrames = 16;
Gates giGates(const GiSamples& samples, const DenoiseStep& denoise, float alpha,
              const std::string& what, const std::string& tag, const std::string& name);

}  // namespace bounce::test
