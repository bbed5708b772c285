// Automatic exposure (src/passes/auto_exposure.h) on lavapipe:
//   - the GPU histogram of a known HDR image (NaN, Inf, negative, black, out-of-range pixels
//     included) equals the CPU's floor(4 log2 Y) count exactly, and the metering is the CPU's;
//   - an all-black frame gets the finite, clamped exposure key * 2^-min, not NaN;
//   - after a jump of the scene's brightness the adapted level follows the documented
//     exponential monotonically and is within 5% of the target exposure on time; a reset snaps;
//   - a scene whose light is 1024x brighter gives the same tonemapped image (exposure is a pure
//     scale: the same up to one fp16 rounding of the display value);
//   - the Cornell box, lit by its lamp alone, is visible with the default settings, exposed
//     where the metering puts middle grey;
//   - fixed exposure (autoExposure = false) is radiance x 2^stops, as before, with no exposure
//     passes in the frame.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "graph/frame_graph.h"
#include "passes/auto_exposure.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "shared/auto_exposure_io.h"
#include "vk/context.h"

namespace bounce {
namespace {

using Bins = std::array<uint32_t, gpu::EXPOSURE_HISTOGRAM_BINS>;

constexpr double kBinsPerStop = gpu::EXPOSURE_BINS_PER_STOP;
constexpr double kHistogramMin = gpu::EXPOSURE_HISTOGRAM_MIN_LOG2;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

double luminance(const glm::vec4& c) {
  return gpu::EXPOSURE_LUMINANCE_R * double(c.x) + gpu::EXPOSURE_LUMINANCE_G * double(c.y) +
         gpu::EXPOSURE_LUMINANCE_B * double(c.z);
}

// The histogram's definition (shared/auto_exposure_io.h), in double: -1 for a pixel not counted.
int binOf(double y) {
  if (!(y > 0.0) || std::isinf(y)) return -1;
  double bin = std::floor(kBinsPerStop * std::log2(y)) - kBinsPerStop * kHistogramMin;
  return int(std::clamp(bin, 0.0, double(gpu::EXPOSURE_HISTOGRAM_BINS - 1)));
}

Bins cpuHistogram(const std::vector<glm::vec4>& pixels) {
  Bins bins{};
  for (const glm::vec4& p : pixels)
    if (int b = binOf(luminance(p)); b >= 0) ++bins[size_t(b)];
  return bins;
}

// The metering of exposure-adapt, in double, over bins (each bin at its centre).
double meteredFromBins(const Bins& bins, const AutoExposureSettings& s) {
  double total = 0.0;
  for (uint32_t c : bins) total += c;
  if (total == 0.0) return kHistogramMin;
  double low = s.lowPercentile * total, high = s.highPercentile * total;
  double below = 0.0, weight = 0.0, weighted = 0.0;
  for (size_t b = 0; b < bins.size(); ++b) {
    double inside = std::max(0.0, std::min(below + bins[b], high) - std::max(below, low));
    weight += inside;
    weighted += inside * (kHistogramMin + (double(b) + 0.5) / kBinsPerStop);
    below += bins[b];
  }
  return weighted / weight;
}

// The same metering without bins: the mean log2 luminance of the pixels between the two
// percentiles (fractional pixels at the ends), from the pixels themselves.
double meteredFromPixels(const std::vector<glm::vec4>& pixels, const AutoExposureSettings& s) {
  std::vector<double> levels;
  for (const glm::vec4& p : pixels)
    if (double y = luminance(p); y > 0.0 && std::isfinite(y))
      levels.push_back(std::clamp(std::log2(y), kHistogramMin, -kHistogramMin));
  std::sort(levels.begin(), levels.end());
  double low = s.lowPercentile * double(levels.size()),
         high = s.highPercentile * double(levels.size());
  double weight = 0.0, weighted = 0.0;
  for (size_t i = 0; i < levels.size(); ++i) {
    double inside = std::max(0.0, std::min(double(i + 1), high) - std::max(double(i), low));
    weight += inside;
    weighted += inside * levels[i];
  }
  return weighted / weight;
}

double exposureFor(double adaptedLog2, const AutoExposureSettings& s, double compensation = 0.0) {
  return std::exp2(std::log2(double(s.key)) - adaptedLog2 + compensation);
}

gpu::ExposureState stateFrom(const graph::DebugView& view) {
  gpu::ExposureState state{};
  EXPECT_EQ(view.bytes.size(), sizeof(state));
  std::memcpy(&state, view.bytes.data(), std::min(view.bytes.size(), sizeof(state)));
  return state;
}

Bins binsOf(const gpu::ExposureState& state) {
  Bins bins{};
  std::copy(std::begin(state.bins), std::end(state.bins), bins.begin());
  return bins;
}

// The two pass units on a graph of their own, fed an HDR image uploaded from the CPU (rgba16f,
// the composite's format): what exposure-histogram sees is exactly the fp16 values kept here.
class ExposureHarness {
 public:
  ExposureHarness(vk::Context& context, uint32_t width, uint32_t height,
                  const AutoExposureSettings& settings = {})
      : context_(context),
        scene_(loadScene("cornell")),
        gpuScene_(context, scene_),
        exposure_(context, gpuScene_, settings),
        width_(width),
        height_(height),
        image_(context, VK_FORMAT_R16G16B16A16_SFLOAT, width, height, 1, 1,
               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                   VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
               "test.hdr", VK_IMAGE_VIEW_TYPE_2D) {
    graph_.requestDebugView("exposure.state");
  }

  // Uploads `pixels` (rounded to fp16) and returns what the image holds.
  std::vector<glm::vec4> upload(const std::vector<glm::vec4>& pixels) {
    std::vector<uint16_t> halves;
    std::vector<glm::vec4> stored;
    for (const glm::vec4& p : pixels) {
      glm::vec4 h;
      for (int c = 0; c < 4; ++c) {
        halves.push_back(glm::packHalf1x16(p[c]));
        h[c] = glm::unpackHalf1x16(halves.back());
      }
      stored.push_back(h);
    }
    std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(halves.data()),
                                   halves.size() * sizeof(uint16_t));
    vk::uploadImage(context_, image_, bytes, 8);
    return stored;
  }

  gpu::ExposureState frame(float deltaSeconds, float compensationStops = 0.0f) {
    graph_.beginFrame();
    graph::ImportedImage imported =
        graph::ImportedImage::from(image_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    imported.externalWrites = true;  // uploaded again between frames
    HdrImage hdr{graph_.importImage("composite.hdr", imported)};
    exposure_.declare(graph_, hdr, compensationStops, deltaSeconds);
    graph_.allocate(context_, {width_, height_});
    context_.submitAndWait([&](VkCommandBuffer cmd) { graph_.execute(cmd); });
    return stateFrom(graph_.readDebugView("exposure.state"));
  }

  void resetHistory() { graph_.resetHistory(); }

 private:
  vk::Context& context_;
  Scene scene_;
  GpuScene gpuScene_;
  AutoExposure exposure_;
  uint32_t width_, height_;
  vk::Image image_;
  graph::FrameGraph graph_;  // after what it imports: destroyed first
};

// Pixels whose luminance lies well inside a random bin (0.2 bin from its edges, far beyond the
// rounding of fp16 and of a float dot product), with random chroma.
std::vector<glm::vec4> randomPixels(size_t count, uint32_t seed, int firstBin, int lastBin) {
  std::vector<glm::vec4> pixels;
  uint32_t state = seed;
  auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (size_t i = 0; i < count; ++i) {
    int bin = firstBin + int(uniform() * (lastBin - firstBin + 1));
    double level = kHistogramMin + (bin + 0.2 + 0.6 * uniform()) / kBinsPerStop;
    glm::dvec3 chroma(0.2 + uniform(), 0.2 + uniform(), 0.2 + uniform());
    double y = luminance(glm::vec4(glm::vec3(chroma), 0.0f));
    glm::dvec3 rgb = chroma * (std::exp2(level) / y);
    pixels.push_back(glm::vec4(glm::vec3(rgb), 1.0f));
  }
  return pixels;
}

class AutoExposureTest : public ::testing::Test {
 protected:
  AutoExposureTest() : context_(vk::contextOptionsFromEnvironment({})) {}
  ~AutoExposureTest() override { EXPECT_EQ(context_.validationErrorCount(), 0u); }
  vk::Context context_;
};

TEST_F(AutoExposureTest, HistogramOfAKnownImageMatchesTheCpuExactly) {
  // 61 x 37: partial groups at the right and bottom edges.
  const uint32_t width = 61, height = 37;
  // Every channel a normal fp16 (2^-14 .. 65504) for chroma ratios up to 6: bins 20 .. 112.
  std::vector<glm::vec4> pixels = randomPixels(size_t(width) * height, 7u, 20, 112);
  const std::vector<glm::vec4> special = {
      {kNaN, 1.0f, 1.0f, 1.0f},
      {kInf, 0.0f, 0.0f, 1.0f},  // not counted
      {-kInf, 1.0f, 1.0f, 1.0f},
      {0.0f, 0.0f, 0.0f, 1.0f},              // not counted
      {-1.0f, -1.0f, -1.0f, 1.0f},           // not counted
      {0.0f, 1.0e-6f, 0.0f, 1.0f},           // fp16 subnormal: bin 0
      {65504.0f, 65504.0f, 65504.0f, 1.0f},  // the last bin
      {-0.5f, 1.0f, 0.25f, 1.0f},            // a negative channel, Y > 0
  };
  for (size_t i = 0; i < special.size(); ++i) pixels[17 * i + 3] = special[i];

  ExposureHarness harness(context_, width, height);
  const std::vector<glm::vec4> stored = harness.upload(pixels);
  const Bins expected = cpuHistogram(stored);
  ASSERT_EQ(expected.front(), 1u);  // the subnormal
  ASSERT_GE(expected.back(), 1u);   // the fp16 maximum
  uint32_t counted = 0;
  for (uint32_t c : expected) counted += c;
  EXPECT_EQ(counted, width * height - 5u);

  // Twice: exposure-adapt clears the histogram after reading it, so the second frame counts the
  // same image again rather than on top of the first.
  for (int frame = 0; frame < 2; ++frame) {
    SCOPED_TRACE(frame);
    const gpu::ExposureState state = harness.frame(1.0f / 60.0f);
    EXPECT_EQ(binsOf(state), expected);
    EXPECT_EQ(state.countedPixels, counted);
    const AutoExposureSettings s;
    EXPECT_NEAR(state.meteredLog2Luminance, meteredFromBins(expected, s), 1e-4);
    // Bins quantise each level by at most half a bin.
    EXPECT_NEAR(state.meteredLog2Luminance, meteredFromPixels(stored, s), 0.5 / kBinsPerStop);
    EXPECT_FLOAT_EQ(state.targetLog2Luminance,
                    std::clamp(state.meteredLog2Luminance, s.minLog2Luminance, s.maxLog2Luminance));
    EXPECT_NEAR(state.exposure / exposureFor(state.adaptedLog2Luminance, s), 1.0, 1e-5);
  }
}

TEST_F(AutoExposureTest, AllBlackFrameGetsTheClampedFiniteExposure) {
  const AutoExposureSettings s;
  ExposureHarness harness(context_, 20, 20, s);
  // Black, and the pixels that must not count: NaN, Inf, negative.
  std::vector<glm::vec4> pixels(400, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  pixels[5] = {kNaN, kNaN, kNaN, 1.0f};
  pixels[6] = {kInf, kInf, kInf, 1.0f};
  pixels[7] = {-2.0f, -2.0f, -2.0f, 1.0f};
  harness.upload(pixels);
  const gpu::ExposureState state = harness.frame(0.0f, 1.0f);
  EXPECT_EQ(state.countedPixels, 0u);
  EXPECT_EQ(state.meteredLog2Luminance, float(kHistogramMin));
  EXPECT_EQ(state.targetLog2Luminance, s.minLog2Luminance);
  ASSERT_TRUE(std::isfinite(state.exposure));
  // key 2^10, one stop of compensation on top.
  EXPECT_NEAR(state.exposure / exposureFor(s.minLog2Luminance, s, 1.0), 1.0, 1e-5);
}

// A jump of 3 stops (the image x8 or /8, an exact fp16 scale), at 30 frames per second: each
// frame the level covers 1 - exp(-dt / tau) of the way; it moves monotonically, never
// overshoots, and is within 5% of the target exposure after tau ln(3 / log2 1.05) seconds, not a
// frame earlier (with the default time constants the distance then lies 1.4% to 2% from the 5%
// line on either side, far beyond float rounding). Each leg starts with a reset, which snaps.
TEST_F(AutoExposureTest, AdaptationAfterAJumpFollowsTheDocumentedExponential) {
  const AutoExposureSettings s;
  const float dt = 1.0f / 30.0f;
  const uint32_t width = 32, height = 32;
  ExposureHarness harness(context_, width, height, s);
  std::vector<glm::vec4> dark = randomPixels(size_t(width) * height, 3u, 56, 72);
  std::vector<glm::vec4> bright = dark;
  for (glm::vec4& p : bright) p *= 8.0f;

  const double withinFivePercent = std::log2(1.05);
  for (const auto& [from, to, tau, name] :
       {std::tuple{&dark, &bright, s.brighteningSeconds, "brighter"},
        std::tuple{&bright, &dark, s.darkeningSeconds, "darker"}}) {
    SCOPED_TRACE(name);
    harness.upload(*from);
    harness.resetHistory();
    const gpu::ExposureState start = harness.frame(dt);
    EXPECT_EQ(start.framesSinceSnap, 0u);
    EXPECT_EQ(start.adaptedLog2Luminance, start.targetLog2Luminance);

    harness.upload(*to);
    double previous = start.adaptedLog2Luminance;
    const double jump = std::abs(harness.frame(0.0f).targetLog2Luminance - previous);
    ASSERT_NEAR(jump, 3.0, 1e-4);  // dt 0: the new target is metered, the level stays
    const int onTime = int(std::ceil(tau * std::log(jump / withinFivePercent) / dt));
    for (int frame = 1; frame <= onTime; ++frame) {
      const gpu::ExposureState state = harness.frame(dt);
      const double target = state.targetLog2Luminance, level = state.adaptedLog2Luminance;
      const double expected = target + (previous - target) * std::exp(-dt / tau);
      EXPECT_NEAR(level, expected, 1e-4) << "frame " << frame;
      EXPECT_LE(std::abs(target - level), std::abs(target - previous)) << "frame " << frame;
      EXPECT_GE((level - previous) * (target - previous), 0.0) << "frame " << frame;
      const bool within = std::abs(target - level) <= withinFivePercent;
      EXPECT_EQ(within, frame == onTime) << "frame " << frame << " of " << onTime;
      EXPECT_NEAR(state.exposure / exposureFor(level, s), 1.0, 1e-5);
      previous = level;
    }
  }
}

// ---- the exposure in the hybrid frame ----------------------------------------------------------

double acesFilmic(double x) {
  const double a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// One unit in the last place of an fp16 value near v (normal range).
double halfUlp(double v) {
  return std::exp2(std::floor(std::log2(std::max(std::abs(v), 6.1e-5))) - 10.0);
}

std::vector<glm::vec4> pixelsOf(const ImageRGBA32F& image) {
  std::vector<glm::vec4> pixels;
  for (size_t i = 0; i < image.pixelCount(); ++i)
    pixels.emplace_back(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2],
                        image.pixels[4 * i + 3]);
  return pixels;
}

struct Rendered {
  ImageRGBA32F composite, display;
  gpu::ExposureState state{};
  std::vector<std::string> passes;
};

Rendered render(vk::Context& context, const Scene& scene, const HybridSettings& settings,
                int frames) {
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("tonemap");
  if (settings.autoExposure) frame.requestDebugView("exposure.state");
  for (int i = 0; i < frames; ++i) frame.render(effectiveCamera(scene));
  Rendered r{frame.debugViewImage("composite"), frame.debugViewImage("tonemap")};
  if (settings.autoExposure) r.state = stateFrom(frame.graph().readDebugView("exposure.state"));
  r.passes = frame.passNames();
  return r;
}

void scaleLight(Scene& scene, float factor) {
  scene.sun.irradiance *= factor;  // a daylight sky follows the sun
  scene.sky.radiance *= factor;
  for (Material& m : scene.materials) m.emissive *= factor;
  for (PunctualLight& l : scene.lights) l.intensity *= factor;
}

// Exposure is a pure scale: with every light 2^10 times brighter the composite is exactly 2^10
// times larger (checked), its histogram moves by exactly 40 bins, the metered level by 10 stops
// and the exposure by 2^-10, up to float rounding (1e-5 relative); the display values then
// differ by at most one fp16 rounding.
TEST_F(AutoExposureTest, LightScaledBy1024GivesTheSameImage) {
  Scene scene = loadScene("sunroom");
  HybridSettings settings;  // automatic exposure, no GI: radiance is linear in the light
  settings.width = 64;
  settings.height = 36;
  settings.skyAmbientStrength = 1.0f;  // sky light on every surface: most pixels lit
  Scene brighter = scene;
  scaleLight(brighter, 1024.0f);
  const Rendered a = render(context_, scene, settings, 2);
  const Rendered b = render(context_, brighter, settings, 2);

  size_t notScaled = 0;  // colour channels (alpha is 1)
  for (size_t i = 0; i < a.composite.pixels.size(); ++i)
    notScaled += i % 4 != 3 && b.composite.pixels[i] != 1024.0f * a.composite.pixels[i];
  ASSERT_EQ(notScaled, 0u) << "the composite is not exactly linear in the light";
  const AutoExposureSettings& s = settings.exposure;
  ASSERT_GT(a.state.targetLog2Luminance, s.minLog2Luminance);  // no clamp in play
  ASSERT_LT(b.state.targetLog2Luminance, s.maxLog2Luminance);
  EXPECT_GT(a.state.countedPixels, a.composite.pixelCount() / 4);

  EXPECT_NEAR(b.state.meteredLog2Luminance - a.state.meteredLog2Luminance, 10.0, 1e-4);
  EXPECT_NEAR(a.state.exposure / (1024.0 * b.state.exposure), 1.0, 1e-5);
  double maxDifference = 0.0, meanA = 0.0, meanB = 0.0;
  for (size_t i = 0; i < a.display.pixels.size(); ++i) {
    const double va = a.display.pixels[i], vb = b.display.pixels[i];
    EXPECT_LE(std::abs(va - vb), halfUlp(std::max(va, vb)) + 1e-6) << "value " << i;
    maxDifference = std::max(maxDifference, std::abs(va - vb));
    meanA += va;
    meanB += vb;
  }
  std::printf("display: mean %.5f vs %.5f, largest difference %.2g\n",
              meanA / a.display.pixels.size(), meanB / b.display.pixels.size(), maxDifference);
  EXPECT_GT(meanA / a.display.pixels.size(), 0.05);  // not a black image that matches trivially
}

// With the default settings (as `bounce render` runs: the mobile preset with ReSTIR GI), the
// Cornell box lit only by its lamp is exposed where the metering puts middle grey, and so
// visible: the pixels above the 95th percentile (5% of those counted) have luminance at least
// the window's mean level less half a bin, so exposure gives them Y >= key 2^-1/8; their
// largest channel is at least Y (the weights sum to 1) and shows at least acesFilmic(key
// 2^-1/8) = 0.25. The image's mean of the largest channel is thus at least 0.05 x the counted
// fraction x 0.25 (0.008 at 80x60); the old fixed exposure, 2^-5, gives 0.004 (measured).
TEST_F(AutoExposureTest, CornellBoxLitByItsLampIsVisibleByDefault) {
  Scene scene = loadScene("cornell");
  HybridSettings settings = presetSettings(Preset::Mobile);
  settings.gi = GiMode::Evolve;
  settings.width = 80;
  settings.height = 60;
  const Rendered r = render(context_, scene, settings, 3);
  const AutoExposureSettings& s = settings.exposure;

  const std::vector<glm::vec4> hdr = pixelsOf(r.composite);
  EXPECT_NEAR(r.state.meteredLog2Luminance, meteredFromPixels(hdr, s), 0.5 / kBinsPerStop);
  ASSERT_GT(r.state.targetLog2Luminance, s.minLog2Luminance);
  EXPECT_NEAR(r.state.exposure / exposureFor(r.state.adaptedLog2Luminance, s), 1.0, 1e-5);

  double largestChannels = 0.0;
  for (size_t i = 0; i < r.display.pixelCount(); ++i) {
    const float* p = r.display.pixels.data() + 4 * i;
    ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
    largestChannels += std::max({p[0], p[1], p[2]});
  }
  const double mean = largestChannels / double(r.display.pixelCount());
  const double counted = double(r.state.countedPixels) / double(r.display.pixelCount());
  const double bound =
      (1.0 - s.highPercentile) * counted * acesFilmic(s.key * std::exp2(-0.5 / kBinsPerStop));
  std::printf("cornell: mean largest channel %.4f, bound %.4f, exposure %.3g\n", mean, bound,
              r.state.exposure);
  EXPECT_GE(mean, bound);
}

// autoExposure = false: no exposure passes, and the display is acesFilmic(radiance x 2^stops)
// up to the fp16 rounding of the display value.
TEST_F(AutoExposureTest, FixedExposureIsTwoToTheStops) {
  Scene scene = loadScene("sunroom");
  HybridSettings settings;
  settings.width = 48;
  settings.height = 27;
  settings.autoExposure = false;
  settings.exposureStops = -3.5f;
  const Rendered r = render(context_, scene, settings, 1);
  for (const std::string& pass : r.passes) EXPECT_EQ(pass.find("exposure"), std::string::npos);
  const double exposure = std::exp2(-3.5);
  size_t lit = 0;
  for (size_t i = 0; i < r.display.pixelCount(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double expected = acesFilmic(double(r.composite.pixels[4 * i + c]) * exposure);
      EXPECT_NEAR(r.display.pixels[4 * i + c], expected, halfUlp(expected) + 1e-6);
      lit += expected > 0.1;
    }
  EXPECT_GT(lit, r.display.pixelCount() / 10);
}

// A scene with no light at all: black, finite, the clamped exposure.
TEST_F(AutoExposureTest, UnlitSceneRendersBlackWithAFiniteExposure) {
  Scene scene = loadScene("cornell");
  scaleLight(scene, 0.0f);
  HybridSettings settings;
  settings.width = 32;
  settings.height = 24;
  const Rendered r = render(context_, scene, settings, 2);
  EXPECT_EQ(r.state.countedPixels, 0u);
  EXPECT_TRUE(std::isfinite(r.state.exposure));
  for (float v : r.display.pixels) ASSERT_TRUE(std::isfinite(v));
  for (size_t i = 0; i < r.display.pixelCount(); ++i)
    EXPECT_EQ(r.display.pixels[4 * i] + r.display.pixels[4 * i + 1] + r.display.pixels[4 * i + 2],
              0.0f);
}

}  // namespace
}  // namespace bounce
