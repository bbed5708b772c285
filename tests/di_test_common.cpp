#include "di_test_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "frame/presets.h"
#include "harness.h"
#include "reference/path_tracer.h"
#include "scene/load.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/scene_options.h"
#include "scene/time_of_day.h"
#include "tools/metrics.h"

namespace bounce::test {

double pixelLuminance(const ImageRGBA32F& image, size_t i) {
  return 0.2126 * image.pixels[4 * i] + 0.7152 * image.pixels[4 * i + 1] +
         0.0722 * image.pixels[4 * i + 2];
}

HybridSettings diSettings(uint32_t width, uint32_t height, const DiSettings& di) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = width;
  settings.height = height;
  settings.shadows.divisor = 1;
  settings.reflections.divisor = 0;
  settings.gi = GiMode::None;
  settings.di = di;
  return settings;
}

ImageRGBA32F meanImage(const std::vector<ImageRGBA32F>& images) {
  ImageRGBA32F mean = images.at(0);
  for (size_t k = 1; k < images.size(); ++k)
    for (size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += images[k].pixels[i];
  for (float& v : mean.pixels) v /= float(images.size());
  return mean;
}

double meanOfColumns(const ImageRGBA32F& image, uint32_t from, uint32_t to) {
  double sum = 0.0;
  size_t n = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = from; x < to; ++x, ++n)
      sum += pixelLuminance(image, size_t(y) * image.width + x);
  return n ? sum / double(n) : 0.0;
}

double maxOfColumns(const ImageRGBA32F& image, uint32_t from, uint32_t to) {
  double m = 0.0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = from; x < to; ++x)
      m = std::max(m, pixelLuminance(image, size_t(y) * image.width + x));
  return m;
}

Scene wallScene() {
  using namespace procedural;
  Scene scene;
  scene.name = "wall";
  const uint32_t white = addMaterial(scene, lambertMaterial("white", glm::vec3(0.8f)));
  MeshBuilder builder;
  addBox(builder.geometry(white), Aabb{{-4.0f, -0.1f, -4.0f}, {4.0f, 0.0f, 4.0f}});
  addBox(builder.geometry(white), Aabb{{-0.05f, 0.0f, -4.0f}, {0.05f, 2.0f, 4.0f}});
  addMeshInstance(scene, builder.build("floor_and_wall"));
  PunctualLight light;
  light.type = PunctualLight::Type::Point;
  light.name = "point";
  light.position = {-1.0f, 0.5f, 0.0f};
  light.intensity = 20.0f;
  scene.lights.push_back(light);
  scene.sun.irradiance = 0.0f;
  scene.sky.radiance = glm::vec3(0.0f);
  Camera camera;
  camera.position = {0.0f, 8.0f, 4.0f};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.verticalFovDegrees = 60.0f;
  scene.camera = camera;
  return scene;
}

WallSequence runWallSequence(const DiSettings& di, const std::string& view) {
  Scene scene = wallScene();
  const Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene,
                    diSettings(WallSequence::kWidth, WallSequence::kHeight, di));
  frame.requestDebugView(view);
  WallSequence run;
  for (int i = 0; i < 8; ++i) frame.render(camera);
  run.before = frame.debugViewImage(view);

  std::vector<PunctualLight> lights = scene.lights;
  lights[0].position.x = 1.0f;
  frame.setLights(lights);
  frame.render(camera);
  run.moved = frame.debugViewImage(view);
  for (int i = 0; i < 23; ++i) frame.render(camera);
  run.settled = frame.debugViewImage(view);

  lights[0].intensity = 0.0f;
  frame.setLights(lights);
  frame.render(camera);
  run.off = frame.debugViewImage(view);

  lights[0] = scene.lights[0];
  frame.setLights(lights);
  frame.render(camera);
  run.back = frame.debugViewImage(view);
  run.validationErrors = uint32_t(context.validationErrorCount());
  return run;
}

Scene cityAtNight(bool lamps) {
  Scene scene = loadScene("city");
  const Sun daySun = scene.sun;
  const Sky daySky = scene.sky;
  applyTimeOfDay(22.0f, daySun, daySky, scene.sun, scene.sky);
  if (!lamps) {
    scene.lights.clear();
    for (Material& m : scene.materials) m.emissive = glm::vec3(0.0f);
  }
  return scene;
}

Camera cityStreetCamera() {
  Camera camera;
  camera.position = {3.0f, 5.0f, 170.0f};
  camera.target = {0.0f, 0.0f, 110.0f};
  camera.verticalFovDegrees = 60.0f;
  return camera;
}

std::vector<ImageRGBA32F> directReference(vk::Context& context, GpuScene& gpuScene,
                                          const Scene& scene, const Camera& camera, uint32_t width,
                                          uint32_t height, int batches, uint32_t spp) {
  ReferencePathTracer tracer(context, gpuScene, scene);
  std::vector<ImageRGBA32F> out;
  for (int b = 0; b < batches; ++b) {
    ReferenceOptions options;
    options.width = width;
    options.height = height;
    options.samplesPerPixel = spp;
    options.maxBounces = 1;
    options.pixelCentre = true;
    options.seed = uint32_t(1 + b);
    out.push_back(tracer.render(camera, options).image);
  }
  return out;
}

namespace {

// Each of `runs` independent runs' mean di-shade image (see compareWithDirectReference).
std::vector<ImageRGBA32F> runMeans(HybridFrame& frame, const Camera& camera, int runs,
                                   int framesPerRun) {
  std::vector<ImageRGBA32F> means;
  for (int run = 0; run < runs; ++run) {
    frame.resetHistory();
    std::vector<ImageRGBA32F> frames;
    for (int i = 0; i < framesPerRun; ++i) {
      frame.render(camera);
      frames.push_back(frame.debugViewImage("di-shade"));
    }
    means.push_back(meanImage(frames));
  }
  return means;
}

// Each 8x8 block's mean luminance in each of a set of independent images: its mean over the
// images and the standard error of that mean (two-pass sample variance over the count).
struct BlockStatistics {
  std::vector<std::vector<double>> perImage;  // [image][block]

  void add(const ImageRGBA32F& image);
  size_t blockCount() const { return perImage.empty() ? 0 : perImage[0].size(); }
  double mean(size_t b) const;
  double standardError(size_t b) const;
};

void BlockStatistics::add(const ImageRGBA32F& image) {
  const uint32_t bx = image.width / 8, by = image.height / 8;
  std::vector<double> blocks(size_t(bx) * by, 0.0);
  for (uint32_t y = 0; y < by * 8; ++y)
    for (uint32_t x = 0; x < bx * 8; ++x)
      blocks[(y / 8) * bx + x / 8] += pixelLuminance(image, size_t(y) * image.width + x) / 64.0;
  perImage.push_back(blocks);
}

double BlockStatistics::mean(size_t b) const {
  double s = 0.0;
  for (const auto& v : perImage) s += v[b];
  return s / double(perImage.size());
}

double BlockStatistics::standardError(size_t b) const {
  const double m = mean(b), n = double(perImage.size());
  double s = 0.0;
  for (const auto& v : perImage) s += (v[b] - m) * (v[b] - m);
  return std::sqrt(s / (n - 1.0) / n);
}

// The block statistics of each of `images`.
BlockStatistics blockStatistics(const std::vector<ImageRGBA32F>& images) {
  BlockStatistics statistics;
  for (const ImageRGBA32F& image : images) statistics.add(image);
  return statistics;
}

// Compares block by block and prints each block beyond `maxZ`, the test's named `testName`.
BlockComparison compareBlocks(const BlockStatistics& test, const BlockStatistics& reference,
                              double maxZ, const char* testName) {
  BlockComparison c;
  for (size_t b = 0; b < test.blockCount(); ++b) {
    const double se = std::hypot(test.standardError(b), reference.standardError(b));
    const double z = std::abs(test.mean(b) - reference.mean(b)) / std::max(se, 1e-12);
    c.worstZ = std::max(c.worstZ, z);
    if (z > maxZ) {
      ++c.outside;
      std::printf("  block %zu: %s %.4f +- %.4f, reference %.4f +- %.4f (%.1f SE)\n", b, testName,
                  test.mean(b), test.standardError(b), reference.mean(b),
                  reference.standardError(b), z);
    }
  }
  return c;
}

// The relMSE that noise alone gives, expected: the mean over pixels and channels of
// (variance of the test's mean + variance of the reference's mean) / (reference^2 + epsilon),
// each variance the sample variance of independent estimates over their count.
double noiseRelMse(const std::vector<ImageRGBA32F>& test,
                   const std::vector<ImageRGBA32F>& reference, const ImageRGBA32F& referenceMean) {
  auto varianceOfMean = [](const std::vector<ImageRGBA32F>& images, size_t k) {
    double sum = 0.0, sumSq = 0.0;
    for (const ImageRGBA32F& image : images) {
      sum += image.pixels[k];
      sumSq += double(image.pixels[k]) * image.pixels[k];
    }
    const double n = double(images.size()), m = sum / n;
    return std::max(sumSq - n * m * m, 0.0) / (n - 1.0) / n;
  };
  double total = 0.0;
  for (size_t i = 0; i < referenceMean.pixelCount(); ++i)
    for (size_t c = 0; c < 3; ++c) {
      const size_t k = 4 * i + c;
      const double r = referenceMean.pixels[k];
      total += (varianceOfMean(test, k) + varianceOfMean(reference, k)) / (r * r + kRelMseEpsilon);
    }
  return total / double(3 * referenceMean.pixelCount());
}

}  // namespace

DirectComparison compareWithDirectReference(vk::Context& context, GpuScene& gpuScene,
                                            const Scene& scene, const Camera& camera,
                                            HybridFrame& frame, uint32_t width, uint32_t height,
                                            const DirectComparisonRuns& runs,
                                            const char* testName) {
  const std::vector<ImageRGBA32F> hybridRuns =
      runMeans(frame, camera, runs.runs, runs.framesPerRun);
  const std::vector<ImageRGBA32F> referenceBatches =
      directReference(context, gpuScene, scene, camera, width, height, runs.batches, runs.spp);
  DirectComparison c;
  c.hybridMean = meanImage(hybridRuns);
  c.referenceMean = meanImage(referenceBatches);
  const BlockStatistics hybrid = blockStatistics(hybridRuns);
  c.blocks = compareBlocks(hybrid, blockStatistics(referenceBatches), runs.maxZ, testName);
  c.blockCount = hybrid.blockCount();
  c.relMse = relativeMeanSquaredError(c.hybridMean, c.referenceMean);
  c.noiseShare = noiseRelMse(hybridRuns, referenceBatches, c.referenceMean);
  c.meanRatio = meanLuminance(c.hybridMean) / meanLuminance(c.referenceMean);
  return c;
}

void PixelVariance::add(const ImageRGBA32F& image) {
  if (sum.empty()) sum.assign(image.pixelCount(), 0.0), sumSq.assign(image.pixelCount(), 0.0);
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const double v = pixelLuminance(image, i);
    sum[i] += v;
    sumSq[i] += v * v;
  }
  ++n;
}

double PixelVariance::meanVariance() const {
  double total = 0.0;
  for (size_t i = 0; i < sum.size(); ++i) {
    const double m = sum[i] / n;
    total += std::max(sumSq[i] - n * m * m, 0.0) / double(n - 1);
  }
  return total / double(sum.size());
}

double oneFrameVariance(HybridFrame& frame, const Camera& camera, int runs) {
  PixelVariance variance;
  for (int run = 0; run < runs; ++run) {
    frame.render(camera);
    variance.add(frame.debugViewImage("di-shade"));
  }
  return variance.meanVariance();
}

}  // namespace bounce::test
