// restir-gi-diag: diagnostics of Evolve's ReSTIR GI chain (src/gi/evolve/restir_gi.h) that print
// measurements instead of checking them, so they live here and not in tests/test_restir_gi.cpp.
// Every run renders the tests' configuration (tests/restir_gi_common.h: Lambert materials,
// pixel-centre camera rays) against a 2,048-spp reference, which is cached in the temp
// directory because it costs minutes on lavapipe. Three modes:
//   - the configuration table (default): for each configuration named in --configs, the last
//     frame's and the mean's relMSE and mean ratio, and the pixels that dominate relMSE, with
//     optional per-frame curves, per-stage values at one pixel and a ratio map;
//   - --jump-config NAME: test_restir_gi's sun jump and camera cut in configuration NAME;
//   - --look DIR: the README's sun-jump pictures.
// Usage and an example: tools/README.md.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "harness.h"
#include "restir_gi_common.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "split_list.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::accumulate;
using test::compare;
using test::Comparison;
using test::giSettings;
using test::luminance;
using test::meanLuminance;
using test::scaled;

struct Options {
  std::string scene = "sunroom";
  std::string resolution = "32x24";
  std::string configs = "default,path,unbiased";
  int frames = 64;
  bool trace = false;
  std::string curve;     // "" (off), "pow2" (frames 2^k) or "all" (every frame)
  std::string stagesAt;  // "x,y"
  bool stagesNeighbours = false;
  std::string pixels;  // "x,y x,y ..."
  bool map = false;
  std::string imagesDir;
  std::string lookDir;
  std::string jumpConfig;
};

constexpr uint32_t kReferenceSpp = 2048;

// The cache's variants of a diagnostic configuration name.
void applyDiagnosticCacheSettings(const std::string& name, ClipmapCacheSettings& cache) {
  if (name.find("stale64") != std::string::npos) cache.maxStaleFrames = 64;
  if (name.find("cap8") != std::string::npos) cache.historyCap = 8.0f;
  if (name.find("cap4") != std::string::npos) cache.historyCap = 4.0f;
  if (name.find("mcache") != std::string::npos) cache = ClipmapCacheSettings{};
  if (name.find("rays16") != std::string::npos)
    cache.raysPerCell = 16, cache.validationRaysPerCell = 0;
  if (name.find("refresh0") != std::string::npos) cache.fullRefreshFrames = 0;
  if (name.find("refresh8") != std::string::npos) cache.fullRefreshFrames = 8;
  if (name.find("refresh16") != std::string::npos) cache.fullRefreshFrames = 16;
  if (name.find("refresh32") != std::string::npos) cache.fullRefreshFrames = 32;
  if (name.find("rcap0") != std::string::npos) cache.fullRefreshHistoryCap = 0.0f;
  if (name.find("rcap3") != std::string::npos) cache.fullRefreshHistoryCap = 3.0f;
  if (name.find("bounces1") != std::string::npos) cache.fullRefreshBounces = 1;
  if (name.find("bounces2") != std::string::npos) cache.fullRefreshBounces = 2;
  if (name.find("bounces4") != std::string::npos) cache.fullRefreshBounces = 4;
  if (name.find("bounces6") != std::string::npos) cache.fullRefreshBounces = 6;
}

// The chain's settings a configuration name asks for: the desktop preset, its second vertex a
// continued path with the prefix "path" or NEE only with "nee", "unbiased" the unbiased
// configuration, and each part below changing one setting ("path-temporal-only",
// "validation3-nobright", ...).
RestirGiSettings diagnosticSettings(const std::string& name) {
  RestirGiSettings gi = presetSettings(Preset::Desktop).restirGi;
  std::string base = name;
  if (name.rfind("path", 0) == 0)
    gi.secondVertex = RestirGiSecondVertex::Path, base = name.substr(4);
  if (name.rfind("nee", 0) == 0) gi.secondVertex = RestirGiSecondVertex::Nee, base = name.substr(3);
  if (name == "unbiased") return RestirGiSettings::unbiased();
  auto has = [&](const char* part) { return base.find(part) != std::string::npos; };
  if (has("temporal-only")) gi.temporalHistorySamples = 1, gi.spatialReuse = false;
  if (has("no-spatial-reuse") || (has("no-spatial") && !has("no-spatial-validation")))
    gi.spatialReuse = false;
  if (has("history1")) gi.temporalHistorySamples = 1;
  if (has("no-tdenoise")) gi.temporalDenoise = false;
  if (has("no-sdenoise")) gi.spatialDenoise = false;
  if (has("resolve1")) gi.resolveSamples = 1;
  if (has("noclip")) gi.denoiseClipSigma = 1e4f;
  for (int m : {1, 2, 3, 4, 5, 10, 20})
    if (has(fmt::format("maxm{}-", m).c_str()) || base.ends_with(fmt::format("maxm{}", m)))
      gi.temporalMaxM = gi.movingTemporalMaxM = float(m);
  if (has("still-cap")) gi.movingTemporalMaxM = gi.temporalMaxM;  // no lower cap in motion
  if (has("history2")) gi.denoiseMaxHistory = 2.0f;
  if (has("history32")) gi.denoiseMaxHistory = 32.0f;
  if (has("history64")) gi.denoiseMaxHistory = 64.0f;
  if (has("no-patch")) gi.patchReservoir = false;
  if (has("no-spatial-validation")) gi.spatialValidation = false;
  if (has("validation3") || has("revalidate3")) gi.validationPeriod = 3;
  if (has("validation3")) gi.historyBrightening = 1.3f;  // the jumping-light configuration
  if (has("passthrough")) gi.validationRadiance = 100.0f, gi.validationDistance = 100.0f;
  if (has("no-denoise")) gi.temporalDenoise = false, gi.resolveSamples = 1;
  if (has("full-res")) gi.divisor = 1;
  if (has("nobright")) gi.historyBrightening = 0.0f;
  if (has("white")) gi.blueNoise = false;
  if (has("jac100")) gi.maxJacobian = 100.0f;
  if (has("nofirefly")) gi.fireflyRatio = 0.0f;
  if (has("firefly3")) gi.fireflyRatio = 3.0f;
  if (has("no-occluder")) gi.occluderVisibility = false;
  if (has("onem")) gi.producerNormalisation = false;
  if (has("fullmip")) gi.materialTextureSide = 0;
  if (has("settle0")) gi.settleFrames = 0;
  if (has("settle4")) gi.settleFrames = 4;
  if (has("settle8")) gi.settleFrames = 8;
  if (has("sscale0")) gi.settleHistoryScale = 0.01f;
  if (has("settle16")) gi.settleFrames = 16;
  if (has("settle24")) gi.settleFrames = 24;
  if (has("sscale1")) gi.settleHistoryScale = 0.1f;
  if (has("sscale3")) gi.settleHistoryScale = 0.3f;
  if (has("bright13")) gi.historyBrightening = 1.3f;
  if (has("bright15")) gi.historyBrightening = 1.5f;
  if (has("bright2")) gi.historyBrightening = 2.0f;
  if (has("age0")) gi.maxSampleAge = 0;
  if (has("age4")) gi.maxSampleAge = 4;
  if (has("age8")) gi.maxSampleAge = 8;
  if (has("age16")) gi.maxSampleAge = 16;
  if (has("age32")) gi.maxSampleAge = 32;
  return gi;
}

// The configuration `name` names: ReSTIR GI and cache settings (above), and the VBuffer
// ("vtrace": one camera ray per pixel, the reference's primary hits; "vraster").
HybridSettings configurationSettings(const std::string& name, uint32_t width, uint32_t height) {
  HybridSettings settings = giSettings(width, height, diagnosticSettings(name));
  applyDiagnosticCacheSettings(name, settings.cache);
  if (name.find("vtrace") != std::string::npos) settings.vbuffer = VBufferMode::Trace;
  if (name.find("vraster") != std::string::npos) settings.vbuffer = VBufferMode::Raster;
  return settings;
}

struct Pixel {
  unsigned x = 0, y = 0;
};

Pixel parsePixel(const std::string& text, const std::string& option) {
  Pixel p;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%u,%u%c", &p.x, &p.y, &rest) != 2)
    fail("{}: expected x,y (pixel coordinates), got '{}'", option, text);
  return p;
}

// The scene, its camera, the image size and the device every run of one invocation shares.
struct Setup {
  explicit Setup(const Options& o)
      : sceneArgument(o.scene),
        size(parseResolution(o.resolution)),
        width(size.width),
        height(size.height),
        scene(loadScene(o.scene)),
        camera(effectiveCamera(scene)),
        context(vk::contextOptionsFromEnvironment()),
        gpuScene(context, scene) {}

  // The reference of this scene and size: the tests' stored one when there is one (checked
  // against a fresh render), else read from the temp directory when an earlier run left it there.
  ImageRGBA32F reference() {
    if (std::filesystem::exists(test::storedReferencePath(scene, width, height, kReferenceSpp)))
      return test::storedReferenceImage(context, gpuScene, scene, camera, width, height,
                                        kReferenceSpp);
    const std::string stem = std::filesystem::path(sceneArgument).stem().string();
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("diag-ref-" + stem + "-" + std::to_string(width) + "x" + std::to_string(height) + ".exr");
    if (std::filesystem::exists(path)) return readImage(path.string());
    ImageRGBA32F image =
        test::referenceImage(context, gpuScene, scene, camera, width, height, kReferenceSpp);
    writeImage(path.string(), image);
    return image;
  }

  std::string sceneArgument;
  Resolution size;
  uint32_t width, height;
  Scene scene;
  Camera camera;
  vk::Context context;
  GpuScene gpuScene;
};

// With --images DIR: the EXR pair DIR/restir-gi-<name>-hybrid.exr and -reference.exr.
void writePair(const Options& o, const std::string& name, const ImageRGBA32F& test,
               const ImageRGBA32F& reference) {
  if (o.imagesDir.empty()) return;
  std::filesystem::create_directories(o.imagesDir);
  const std::string stem = o.imagesDir + "/restir-gi-" + name;
  writeImage(stem + "-hybrid.exr", test);
  writeImage(stem + "-reference.exr", reference);
}

// --stages-at: the value of each stage of the chain at one render pixel (the GI pixel under it
// for the half-resolution views), averaged over frames. In the chain's order: where a value
// departs from the reference's is where a leak or a bias starts.
class StageProbe {
 public:
  StageProbe(Pixel at, bool cacheRuns) : at_(at) {
    for (const char* stage :
         {"cache", "gi.hit-radiance", "gi.candidate-estimate", "gi.reservoir-estimate",
          "gi.spatial-0-estimate", "gi.spatial-1-estimate", "gi.validated-estimate",
          "gi.patched-estimate", "gi.resolve-occlusion", "gi.resolved", "gi.temporal-denoised",
          "gi.diffuse", "gbuffer.base-color", "composite"})
      if (cacheRuns || std::string(stage) != "cache") stages_.push_back(stage);
    means_.assign(stages_.size(), 0.0);
  }

  Pixel at() const { return at_; }

  void request(HybridFrame& frame) const {
    for (const std::string& stage : stages_) frame.requestDebugView(stage);
  }

  // Adds this frame's values with the given weight.
  void add(const HybridFrame& frame, uint32_t width, uint32_t height, double weight) {
    for (size_t k = 0; k < stages_.size(); ++k) {
      const ImageRGBA32F view = frame.debugViewImage(stages_[k]);
      const size_t x = at_.x * view.width / width, y = at_.y * view.height / height;
      means_[k] += weight * luminance(view, y * view.width + x);
    }
  }

  void print() const {
    std::printf("  stages at (%u,%u):", at_.x, at_.y);
    for (size_t k = 0; k < stages_.size(); ++k)
      std::printf(" %s %.3f", stages_[k].c_str(), means_[k]);
    std::printf("\n");
  }

 private:
  Pixel at_;
  std::vector<std::string> stages_;
  std::vector<double> means_;
};

// The last frame's 5x3 neighbourhood of p in a few views and in the reference: which surface is
// which around a leak.
void printNeighbourhoods(const HybridFrame& frame, const ImageRGBA32F& reference, Pixel p,
                         uint32_t width) {
  for (const char* view :
       {"gbuffer.normals", "gbuffer.base-color", "gi.resolved", "gi.diffuse", "composite"}) {
    ImageRGBA32F v = frame.debugViewImage(view);
    std::printf("  %s around (%u,%u):\n", view, p.x, p.y);
    for (int dy = -1; dy <= 1; ++dy) {
      std::printf("   ");
      for (int dx = -2; dx <= 2; ++dx) {
        glm::vec4 c = v.at(int(p.x) + dx, int(p.y) + dy);
        std::printf(" (%.2f %.2f %.2f %.2f)", c.x, c.y, c.z, c.w);
      }
      std::printf("\n");
    }
  }
  std::printf("  reference around:\n");
  for (int dy = -1; dy <= 1; ++dy) {
    std::printf("   ");
    for (int dx = -2; dx <= 2; ++dx)
      std::printf(" %.3f",
                  luminance(reference, size_t(int(p.y) + dy) * width + size_t(int(p.x) + dx)));
    std::printf("\n");
  }
}

// The mean's luminance at each listed pixel against the reference's.
void printPixels(const std::string& list, const ImageRGBA32F& mean, const ImageRGBA32F& reference,
                 uint32_t width, uint32_t height) {
  for (const std::string& item : splitList(list, ' ')) {
    Pixel p = parsePixel(item, "--pixels");
    if (p.x < width && p.y < height)
      std::printf("  pixel (%u,%u): %.3f vs %.3f\n", p.x, p.y,
                  luminance(mean, size_t(p.y) * width + p.x),
                  luminance(reference, size_t(p.y) * width + p.x));
  }
}

// The mean's ratio to the reference per pixel (luminance), one character each:
// '-' < 0.8 <= 'd' < 0.95 <= '.' < 1.05 <= 'b' < 1.2 <= '+'; ' ' where the reference is black.
void printRatioMap(const ImageRGBA32F& mean, const ImageRGBA32F& reference, uint32_t width,
                   uint32_t height) {
  for (uint32_t y = 0; y < height; ++y) {
    std::string row = "  |";
    for (uint32_t x = 0; x < width; ++x) {
      double r = luminance(reference, size_t(y) * width + x);
      double ratio = luminance(mean, size_t(y) * width + x) / std::max(r, 1e-9);
      row += r < 0.01       ? ' '
             : ratio < 0.8  ? '-'
             : ratio < 0.95 ? 'd'
             : ratio < 1.05 ? '.'
             : ratio < 1.2  ? 'b'
                            : '+';
    }
    std::printf("%s|\n", row.c_str());
  }
}

// --curve: the composite's error at frame n, with the cache's and the candidates' means.
void printCurvePoint(const HybridFrame& frame, const ImageRGBA32F& reference, int n,
                     bool cacheRuns) {
  const Comparison now = compare(frame.debugViewImage("composite"), reference);
  std::printf("  frame %d: relMSE %.4f ratio %.4f cache %.4f candidates %.4f\n", n, now.relMse,
              now.meanRatio, cacheRuns ? meanLuminance(frame.debugViewImage("cache")) : 0.0,
              meanLuminance(frame.debugViewImage("gi-resolve-diffuse-rays")));
}

// --trace: the means of the candidates, of temporal reuse and of the composite in frame i.
void printTracePoint(const HybridFrame& frame, int i) {
  std::printf("  frame %d: candidates %.4f temporal %.4f composite %.4f\n", i,
              meanLuminance(frame.debugViewImage("gi-resolve-diffuse-rays")),
              meanLuminance(frame.debugViewImage("gi-restir-temporal")),
              meanLuminance(frame.debugViewImage("composite")));
}

// One configuration of the table: `frames` frames of a static view; the means are over the
// second half of them (the first converges).
void runConfiguration(const Options& o, Setup& setup, const ImageRGBA32F& reference,
                      const std::string& name) {
  const uint32_t width = setup.width, height = setup.height;
  const HybridSettings settings = configurationSettings(name, width, height);
  const bool cacheRuns = settings.restirGi.secondVertex == RestirGiSecondVertex::Cache;
  HybridFrame frame(setup.context, setup.gpuScene, setup.scene, settings);
  for (const char* view : {"composite", "gi-restir-temporal", "gi-resolve-diffuse-rays"})
    frame.requestDebugView(view);
  if (!o.curve.empty() && cacheRuns) frame.requestDebugView("cache");
  std::optional<StageProbe> probe;
  if (!o.stagesAt.empty()) {
    probe.emplace(parsePixel(o.stagesAt, "--stages-at"), cacheRuns);
    probe->request(frame);
    frame.requestDebugView("gbuffer.normals");
  }

  const int frames = o.frames, secondHalf = frames - frames / 2;
  ImageRGBA32F sum;
  double frameRelMse = 0.0;  // mean of each frame's relMSE: noise, boiling and bias
  for (int i = 0; i < frames; ++i) {
    frame.render(setup.camera);
    if (i >= frames / 2) {
      if (probe) probe->add(frame, width, height, 1.0 / double(secondHalf));
      accumulate(sum, frame.debugViewImage("composite"));
      frameRelMse +=
          compare(frame.debugViewImage("composite"), reference).relMse / double(secondHalf);
    }
    const bool powerOfTwo = ((i + 1) & i) == 0 && i >= 3;
    if (!o.curve.empty() && (powerOfTwo || o.curve == "all"))
      printCurvePoint(frame, reference, i + 1, cacheRuns);
    if (o.trace && i >= frames - 16) printTracePoint(frame, i);
  }

  const ImageRGBA32F mean = scaled(sum, 1.0f / float(secondHalf));
  const Comparison last = compare(frame.debugViewImage("composite"), reference);
  const Comparison meanError = compare(mean, reference);
  std::printf(
      "%s: last frame relMSE %.4f ratio %.4f; mean of 2nd half relMSE %.4f ratio %.4f; "
      "frames of the 2nd half: mean relMSE %.4f\n",
      name.c_str(), last.relMse, last.meanRatio, meanError.relMse, meanError.meanRatio,
      frameRelMse);
  writePair(o, "diag-" + name, frame.debugViewImage("composite"), reference);
  test::printWorstPixels(mean, reference, 8);
  if (probe && o.stagesNeighbours) printNeighbourhoods(frame, reference, probe->at(), width);
  if (probe) probe->print();
  if (!o.pixels.empty()) printPixels(o.pixels, mean, reference, width, height);
  writePair(o, "diag-mean-" + name, mean, reference);
  if (o.map) printRatioMap(mean, reference, width, height);
}

void runConfigurations(const Options& o) {
  Setup setup(o);
  const ImageRGBA32F reference = setup.reference();
  for (const std::string& name : splitList(o.configs, ','))
    runConfiguration(o, setup, reference, name);
}

// test_restir_gi's sun jump and camera cut (test::runSunJump) in another configuration; with
// --trace every frame's error and the mean of each stage of the chain.
void runJump(const Options& o) {
  Setup setup(o);
  const ImageRGBA32F reference = setup.reference();
  const std::vector<std::string> stages = o.trace
                                              ? std::vector<std::string>{"cache",
                                                                         "gi.hit-radiance",
                                                                         "gi-resolve-diffuse-rays",
                                                                         "gi-restir-temporal",
                                                                         "gi.resolved",
                                                                         "gi.temporal-denoised"}
                                              : std::vector<std::string>{};
  const test::SunJumpRun run = test::runSunJump(
      setup.context, setup.gpuScene, setup.scene, setup.camera,
      configurationSettings(o.jumpConfig, setup.width, setup.height), reference, stages);
  test::printSunJump(run, o.trace);
}

// The README's sun-jump pictures: sunroom 240x135, desktop preset, traced VBuffer; 48 frames
// under the mirrored sun, then the sun jumps back; the composite before the jump and 1, 2, 4, 8,
// 10, 16 and 64 frames after it, as DIR/before.png and DIR/after-N.png.
void writeLookPictures(const std::string& dir) {
  std::filesystem::create_directories(dir);
  const uint32_t width = 240, height = 135;
  Scene scene = loadScene("sunroom");
  Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridSettings settings = giSettings(width, height, presetSettings(Preset::Desktop).restirGi);
  settings.vbuffer = VBufferMode::Trace;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  Sun mirrored = scene.sun;
  mirrored.direction =
      glm::vec3(-mirrored.direction.x, mirrored.direction.y, -mirrored.direction.z);
  frame.setSunAndSky(mirrored, scene.sky);
  for (int i = 0; i < 48; ++i) frame.render(camera);
  const float exposure = 0.03f;
  writeImage(dir + "/before.png", frame.debugViewImage("composite"), exposure);
  frame.setSunAndSky(scene.sun, scene.sky);
  for (int i = 1; i <= 64; ++i) {
    frame.render(camera);
    if (i == 1 || i == 2 || i == 4 || i == 8 || i == 10 || i == 16 || i == 64)
      writeImage(dir + "/after-" + std::to_string(i) + ".png", frame.debugViewImage("composite"),
                 exposure);
  }
}

void addOptions(CLI::App& app, Options& o) {
  app.add_option("--scene", o.scene, "Built-in scene name or .gltf/.glb path")
      ->capture_default_str();
  app.add_option("--res", o.resolution, "Image size WxH")->capture_default_str();
  app.add_option("--configs", o.configs,
                 "Comma-separated configuration names (tools/README.md), e.g. "
                 "default,path,unbiased,temporal-only,no-denoise,validation3")
      ->capture_default_str();
  app.add_option("--frames", o.frames, "Frames per configuration; means are over the 2nd half")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.add_flag("--trace", o.trace,
               "Per-frame means: the last 16 frames' candidates, temporal and composite (with "
               "--jump-config: every frame and each stage)");
  app.add_flag("--curve{pow2}", o.curve,
               "Convergence curve: relMSE and mean ratio at frames 4, 8, 16, ... (--curve=all: "
               "every frame)");
  app.add_option("--stages-at", o.stagesAt,
                 "X,Y: each stage's luminance at that pixel, mean over the 2nd half");
  app.add_flag("--stages-neighbours", o.stagesNeighbours,
               "With --stages-at: the last frame's 5x3 neighbourhood in a few views");
  app.add_option("--pixels", o.pixels, "\"x,y x,y ...\": those pixels' mean against the reference");
  app.add_flag("--map", o.map, "A map of the mean's luminance ratio to the reference, per pixel");
  app.add_option("--images", o.imagesDir,
                 "Write each configuration's last frame and mean with the reference as EXR "
                 "pairs into this directory");
  app.add_option("--look", o.lookDir,
                 "Instead of the table: write the README's sun-jump pictures (sunroom 240x135) "
                 "into this directory");
  app.add_option("--jump-config", o.jumpConfig,
                 "Instead of the table: test_restir_gi's sun jump and camera cut in this "
                 "configuration (the test's is validation3)");
}

// Malformed option text gets its error before minutes of rendering.
void checkOptions(const Options& o) {
  parseResolution(o.resolution);
  if (!o.stagesAt.empty()) parsePixel(o.stagesAt, "--stages-at");
  for (const std::string& item : splitList(o.pixels, ' ')) parsePixel(item, "--pixels");
}

int runDiagnostics(const Options& o) {
  checkOptions(o);
  if (!o.lookDir.empty())
    writeLookPictures(o.lookDir);
  else if (!o.jumpConfig.empty())
    runJump(o);
  else
    runConfigurations(o);
  return 0;
}

}  // namespace
}  // namespace bounce

int main(int argc, char** argv) {
  CLI::App app{"ReSTIR GI diagnostics against the reference path tracer (tools/README.md)",
               "restir-gi-diag"};
  bounce::Options options;
  bounce::addOptions(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return bounce::runDiagnostics(options);
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "restir-gi-diag: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "restir-gi-diag: internal error: %s\n", e.what());
    return 3;
  }
}
