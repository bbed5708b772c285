#include "restir_gi_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <utility>

#include "core/error.h"
#include "frame/hybrid_frame.h"
#include "harness.h"
#include "reference/path_tracer.h"
#include "scene/animation.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/metrics.h"

namespace bounce::test {

void accumulate(ImageRGBA32F& sum, const ImageRGBA32F& image) {
  if (sum.pixels.empty()) {
    sum = image;
    return;
  }
  for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += image.pixels[i];
}

ImageRGBA32F scaled(ImageRGBA32F image, float s) {
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (i % 4 != 3) image.pixels[i] *= s;
  return image;
}

double luminance(const ImageRGBA32F& image, size_t i) {
  return 0.2126 * image.pixels[4 * i] + 0.7152 * image.pixels[4 * i + 1] +
         0.0722 * image.pixels[4 * i + 2];
}

Comparison compare(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  return {relativeMeanSquaredError(test, reference),
          meanLuminance(test) / meanLuminance(reference)};
}

namespace {

std::string describeCamera(const Camera& c) {
  char text[256];
  std::snprintf(text, sizeof text,
                "position %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov %.9g",
                c.position.x, c.position.y, c.position.z, c.target.x, c.target.y, c.target.z,
                c.up.x, c.up.y, c.up.z, c.verticalFovDegrees);
  return text;
}

// Mean luminance of each cell of an 8x6 grid over the image (cells at least one pixel wide).
std::vector<double> gridMeans(const ImageRGBA32F& image) {
  const int columns = std::min(8, image.width), rows = std::min(6, image.height);
  std::vector<double> sum(size_t(columns * rows), 0.0), count(sum.size(), 0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const size_t cell = size_t(y * rows / image.height * columns + x * columns / image.width);
      sum[cell] += luminance(image, size_t(y) * image.width + x);
      count[cell] += 1.0;
    }
  for (size_t i = 0; i < sum.size(); ++i) sum[i] /= count[i];
  return sum;
}

}  // namespace

// How far the stored image's grid means lie from a fresh render's, in units of that render's
// own noise: two half renders a and b (other seeds) give check = (a + b) / 2, whose cell
// variance V / 2 is estimated by ((a - b) / 2)^2. With the stored image converged, the sum of
// (check - stored)^2 over the sum of ((a - b) / 2)^2 is about 1 (an F(48, 48) ratio: above 2.6
// one time in a thousand); a stale image (another scene, camera or path tracer) is far above.
double referenceStaleness(const ImageRGBA32F& stored, const ImageRGBA32F& a,
                          const ImageRGBA32F& b) {
  const std::vector<double> s = gridMeans(stored), ma = gridMeans(a), mb = gridMeans(b);
  double difference = 0.0, noise = 0.0;
  for (size_t i = 0; i < s.size(); ++i) {
    const double check = 0.5 * (ma[i] + mb[i]);
    difference += (check - s[i]) * (check - s[i]);
    noise += 0.25 * (ma[i] - mb[i]) * (ma[i] - mb[i]);
  }
  return difference / std::max(noise, 1e-30);
}

ImageRGBA32F referenceImage(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                            const Camera& camera, uint32_t width, uint32_t height, uint32_t spp,
                            uint32_t seed) {
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions options;
  options.width = width;
  options.height = height;
  options.samplesPerPixel = spp;
  options.maxBounces = 16;
  options.seed = seed;
  options.lambert = true;
  options.pixelCentre = true;
  return tracer.render(camera, options).image;
}

std::string storedReferencePath(const Scene& scene, uint32_t width, uint32_t height, uint32_t spp) {
  return std::string(BOUNCE_SOURCE_DIR) + "/tests/data/references/" + scene.name + "_" +
         std::to_string(width) + "x" + std::to_string(height) + "_" + std::to_string(spp) +
         "spp.exr";
}

ImageRGBA32F storedReferenceImage(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                                  const Camera& camera, uint32_t width, uint32_t height,
                                  uint32_t spp) {
  const std::string path = storedReferencePath(scene, width, height, spp);
  const std::string name = std::filesystem::path(path).filename().string();
  const std::string regenerate =
      "; regenerate the stored references with BOUNCE_REGENERATE_REFERENCES=1 (docs/testing.md)";
  const ImageMetadata expected = {
      {"bounce.reference.camera", describeCamera(camera)},
      {"bounce.reference.options", "lambert, pixel centres, 16 bounces, seed 1"}};
  const char* flag = std::getenv("BOUNCE_REGENERATE_REFERENCES");
  if (flag && std::string(flag) == "1") {
    ImageRGBA32F image = referenceImage(context, gpuScene, scene, camera, width, height, spp);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    writeExr(path, image, expected);
    std::printf("stored reference written: %s\n", path.c_str());
    return image;
  }
  if (!std::filesystem::exists(path)) {
    std::printf("no stored reference %s: rendering it\n", name.c_str());
    return referenceImage(context, gpuScene, scene, camera, width, height, spp);
  }
  const ImageMetadata stored = readExrMetadata(path);
  for (const auto& [key, value] : expected) {
    auto it = std::find_if(stored.begin(), stored.end(),
                           [&](const auto& entry) { return entry.first == key; });
    if (it == stored.end() || it->second != value)
      throw Error(path + ": stored with " + key + " '" +
                  (it == stored.end() ? std::string("(none)") : it->second) +
                  "', the test asks for '" + value + "'" + regenerate);
  }
  ImageRGBA32F image = readImage(path);
  if (image.width != int(width) || image.height != int(height))
    throw Error(path + ": not " + std::to_string(width) + "x" + std::to_string(height) +
                regenerate);
  const uint32_t half = std::max(1u, spp / 32);
  const ImageRGBA32F a = referenceImage(context, gpuScene, scene, camera, width, height, half, 2);
  const ImageRGBA32F b = referenceImage(context, gpuScene, scene, camera, width, height, half, 3);
  const double ratio = referenceStaleness(image, a, b);
  std::printf("stored reference %s: a %u-spp check differs from it by %.2fx its own noise\n",
              name.c_str(), 2 * half, ratio);
  if (ratio > 4.0)
    throw Error(path + ": a fresh " + std::to_string(2 * half) + "-spp render differs from it by " +
                std::to_string(ratio) +
                "x its own noise (about 1 expected): the scene, camera or path tracer changed" +
                regenerate);
  return image;
}

HybridSettings giSettings(uint32_t width, uint32_t height, const RestirGiSettings& gi) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = width;
  settings.height = height;
  settings.shadows.divisor = 1;
  settings.lambert = true;
  settings.gi = GiMode::Evolve;
  settings.restirGi = gi;
  return settings;
}

void printWorstPixels(const ImageRGBA32F& test, const ImageRGBA32F& reference, size_t count) {
  std::vector<std::pair<double, size_t>> errors;
  double total = 0.0;
  for (size_t i = 0; i < test.pixelCount(); ++i) {
    double e = 0.0;
    for (int c = 0; c < 3; ++c) {
      double r = reference.pixels[4 * i + c], d = test.pixels[4 * i + c] - r;
      e += d * d / (r * r + 0.01) / 3.0;
    }
    errors.push_back({e, i});
    total += e;
  }
  count = std::min(count, errors.size());
  std::partial_sort(errors.begin(), errors.begin() + long(count), errors.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  const size_t n = errors.size(), width = test.width;
  double worst = 0.0;
  std::printf("  largest shares of relMSE %.4f:", total / double(n));
  for (size_t k = 0; k < count; ++k) {
    worst += errors[k].first;
    std::printf(" (%zu,%zu) %.4f [%.3f vs %.3f]", errors[k].second % width,
                errors[k].second / width, errors[k].first / double(n),
                luminance(test, errors[k].second), luminance(reference, errors[k].second));
  }
  std::printf("\n  relMSE without those %zu pixels: %.4f\n", count, (total - worst) / double(n));
}

double SunJumpRun::recovered() const {
  return (after.at(7) + after.at(8) + after.at(9)) / 3.0;
}

double SunJumpRun::converged() const {
  double sum = 0.0;
  for (size_t i = 48; i < 64; ++i) sum += after.at(i);
  return sum / 16.0;
}

SunJumpRun runSunJump(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                      const Camera& camera, const HybridSettings& settings,
                      const ImageRGBA32F& reference, const std::vector<std::string>& stages) {
  SunJumpRun run;
  run.sceneName = scene.name;
  run.stages = stages;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  for (const std::string& stage : stages) frame.requestDebugView(stage);
  Sun mirrored = scene.sun;
  mirrored.direction =
      glm::vec3(-mirrored.direction.x, mirrored.direction.y, -mirrored.direction.z);
  frame.setSunAndSky(mirrored, scene.sky);
  for (int i = 0; i < 48; ++i) frame.render(camera);
  run.before = relativeMeanSquaredError(frame.debugViewImage("composite"), reference);

  frame.setSunAndSky(scene.sun, scene.sky);
  for (int i = 1; i <= 64; ++i) {
    frame.render(camera);
    run.after.push_back(relativeMeanSquaredError(frame.debugViewImage("composite"), reference));
    if (stages.empty()) continue;
    std::vector<double>& means = run.stageMeans.emplace_back();
    for (const std::string& stage : stages)
      means.push_back(meanLuminance(frame.debugViewImage(stage)));
  }

  Camera cut = camera;
  cut.position = camera.position + 0.5f * (camera.target - camera.position);
  frame.resetHistory();
  frame.render(cut);
  const ImageRGBA32F first = frame.debugViewImage("composite");
  run.firstCutLuminance = meanLuminance(first);
  run.firstCutNonFinite = countNonFinitePixels(first);
  for (int i = 0; i < 16; ++i) frame.render(cut);
  run.settledCutLuminance = meanLuminance(frame.debugViewImage("composite"));
  return run;
}

void printSunJump(const SunJumpRun& run, bool everyFrame) {
  std::printf("%s sun jump, composite relMSE: before the jump %.4f, after:", run.sceneName.c_str(),
              run.before);
  for (size_t k = 0; k < run.after.size(); ++k) {
    const size_t i = k + 1;
    if (i <= 12 || i % 8 == 0 || everyFrame) std::printf(" %zu:%.4f", i, run.after[k]);
    if (k < run.stageMeans.size()) {
      std::printf(" (stages");
      for (double mean : run.stageMeans[k]) std::printf(" %.3f", mean);
      std::printf(")");
    }
  }
  std::printf("\n  composite: frames 8-10 %.4f, converged (49-64) %.4f: %.2fx\n", run.recovered(),
              run.converged(), run.recovered() / run.converged());
  std::printf("camera cut: mean luminance of the first frame %.4g, after 16 frames %.4g\n",
              run.firstCutLuminance, run.settledCutLuminance);
}

SunroomSunJump runSunroomSunJump(const HybridSettings& settings) {
  Scene scene = loadScene("sunroom");
  const Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  const ImageRGBA32F reference =
      storedReferenceImage(context, gpuScene, scene, camera, settings.width, settings.height, 2048);
  SunroomSunJump jump;
  jump.run = runSunJump(context, gpuScene, scene, camera, settings, reference);
  printSunJump(jump.run, false);
  jump.validationErrors = context.validationErrorCount();
  return jump;
}

AnimatedRun runAnimated(const std::string& sceneName, HybridSettings settings, int frames,
                        const std::vector<std::string>& views) {
  Scene scene = loadScene(sceneName);
  Camera camera = effectiveCamera(scene);
  vk::ContextOptions options = vk::contextOptionsFromEnvironment();
  options.validation = true;
  vk::Context context(options);
  GpuScene gpuScene(context, scene);
  settings.cache.raysPerCell = 1;
  settings.cache.validationRaysPerCell = 1;
  HybridFrame frame(context, gpuScene, scene, settings);
  for (const std::string& view : views) frame.requestDebugView(view);
  CameraPath path = swayCameraPath(camera, 20.0f, 0.3f, 8.0f);
  std::vector<glm::mat4> transforms(scene.instances.size());
  for (size_t i = 0; i < transforms.size(); ++i) transforms[i] = scene.instances[i].transform;
  AnimatedRun run;
  for (int i = 0; i < frames; ++i) {
    float t = float(i) / 30.0f;
    evaluateTransforms(scene.animation, t, {}, transforms);
    frame.setInstanceTransforms(transforms);
    Sun sun = scene.sun;
    float a = 0.5f * t;
    sun.direction = glm::normalize(glm::vec3(std::cos(a), -0.8f, std::sin(a)));
    frame.setSunAndSky(sun, scene.sky);
    frame.render(evaluateCameraPath(path, t));
    if (i % 8 == 7)
      for (const std::string& view : views)
        run.nonFinite += countNonFinitePixels(frame.debugViewImage(view));
  }
  run.validationErrors = context.validationErrorCount();
  return run;
}

FurnaceRun runFurnace(vk::Context& context, const HybridSettings& settings,
                      const std::vector<std::string>& stages, int frames) {
  const int averaged = frames - 32;
  Scene scene = loadScene("furnace");
  Camera camera = effectiveCamera(scene);
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  for (const std::string& stage : stages) frame.requestDebugView(stage);
  FurnaceRun run;
  run.frames = frames;
  run.stageMeans.assign(stages.size(), 0.0);
  run.lowest = 1e9f;
  for (int i = 0; i < frames; ++i) {
    frame.render(camera);
    if (i < frames - averaged) continue;
    ImageRGBA32F image = frame.debugViewImage("composite");
    run.mean += meanLuminance(image) / averaged;
    for (size_t k = 0; k < image.pixelCount(); ++k) {
      run.lowest = std::min(run.lowest, float(luminance(image, k)));
      run.highest = std::max(run.highest, float(luminance(image, k)));
    }
    for (size_t s = 0; s < stages.size(); ++s)
      run.stageMeans[s] += meanLuminance(frame.debugViewImage(stages[s])) / averaged;
  }
  return run;
}

void printFurnace(const char* label, const HybridSettings& settings, const FurnaceRun& run,
                  const std::vector<std::string>& stages) {
  std::printf("%s furnace %ux%u, frames 33-%d: composite %.4f (analytic 2), pixels %.3f..%.3f\n",
              label, settings.width, settings.height, run.frames, run.mean, run.lowest,
              run.highest);
  for (size_t s = 0; s < stages.size() && s < run.stageMeans.size(); ++s)
    std::printf("  %s %.4f\n", stages[s].c_str(), run.stageMeans[s]);
}

}  // namespace bounce::test
