// specular-diag: the `spheres` scene's composite against the reference per sphere (row =
// material, column = roughness), for a list of frame configurations, so that a shortfall can be
// traced to a roughness range, a material, a GI mode, the reflection rays or a light. It prints
// measurements instead of checking them (tests/test_specular.cpp holds the checks).
// The reference (pixel centres, as the frame shades them) is cached in the temp directory per
// scene, lighting and size. Usage and an example: docs/tools.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "core/error.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "lighting/light_table.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/procedural/builtin_scenes.h"
#include "scene/scene_options.h"
#include "split_list.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using procedural::kSpheresColumns;
using procedural::kSpheresRoughness;
using procedural::kSpheresRows;

struct Options {
  std::string scene = "spheres";
  std::string resolution = "192x108";
  std::string configs = "evolve+d2,evolve+d0";
  std::string sun, sky;
  int frames = 16;
  int averaged = 8;
  uint32_t spp = 256;
  std::string imagesDir;
  std::string testImage;  // compare this EXR instead of rendering
  std::string views;      // debug views whose per-row means are printed
  bool interior = false;
  bool noSun = false;
  bool lambert = false;
  std::string sphere;  // "R,C": print that sphere's pixels
  uint32_t maxBounces = 16;
  uint32_t seed = 1;
};

// A configuration name is a '+'-separated list of parts: the GI mode (none, cache, evolve),
// dN (reflection divisor N), maxrX (maxTracedRoughness X), mirrorX (mirrorRoughness X),
// regX (hitRegularization X), ambientX (skyAmbientStrength X), full-mip (reflection textures at
// full resolution), mobile, no-reuse, no-denoise (the reflection chain's stages off), no-di (ReSTIR
// DI off).
HybridSettings configurationSettings(const std::string& name, uint32_t width, uint32_t height) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  for (const std::string& part : splitList(name, '+'))
    if (part == "mobile") settings = presetSettings(Preset::Mobile);
  settings.width = width;
  settings.height = height;
  settings.gi = GiMode::Evolve;
  for (const std::string& part : splitList(name, '+')) {
    auto number = [&](const char* prefix) { return std::stof(part.substr(std::strlen(prefix))); };
    if (part == "mobile") continue;
    if (std::optional<GiMode> mode = giModeFromName(part)) {
      settings.gi = *mode;
    } else if (part.rfind("d", 0) == 0 && part.size() > 1 && std::isdigit(part[1])) {
      settings.reflections.divisor = uint32_t(number("d"));
    } else if (part.rfind("maxr", 0) == 0) {
      settings.reflections.maxTracedRoughness = number("maxr");
    } else if (part.rfind("reg", 0) == 0) {
      settings.reflections.hitRegularization = number("reg");
    } else if (part.rfind("mirror", 0) == 0) {
      settings.reflections.mirrorRoughness = number("mirror");
    } else if (part.rfind("ambient", 0) == 0) {
      settings.skyAmbientStrength = number("ambient");
    } else if (part == "full-mip") {
      settings.reflections.materialTextureSide = 0;
    } else if (part == "shared-mirrors") {
      settings.reflections.mirrorsAtFullResolution = false;
    } else if (part == "no-reuse") {
      settings.reflections.reuse = false;
    } else if (part == "no-denoise") {
      settings.reflectionDenoise.enabled = false;
    } else if (part == "no-di") {
      settings.di.mode = DiMode::Off;
    } else {
      fail("--configs: unknown part '{}' in '{}'", part, name);
    }
  }
  validate(settings);
  return settings;
}

// Sums of composite and reference luminance over one instance's pixels.
struct Sums {
  double hybrid = 0.0, reference = 0.0;
  int pixels = 0;
  void add(const Sums& o) { hybrid += o.hybrid, reference += o.reference, pixels += o.pixels; }
  double ratio() const { return reference > 0.0 ? hybrid / reference : 0.0; }
};

std::vector<glm::uvec4> instanceIds(const HybridFrame& frame) {
  const graph::DebugView& view = frame.graph().readDebugView("vbuffer.ids");
  std::vector<glm::uvec4> ids(view.bytes.size() / sizeof(glm::uvec4));
  std::memcpy(ids.data(), view.bytes.data(), ids.size() * sizeof(glm::uvec4));
  return ids;
}

// Per instance: sums over its pixels (with `interior`, only those whose 3 x 3 neighbourhood is
// the same instance: silhouettes left out).
std::map<uint32_t, Sums> instanceSums(const std::vector<glm::uvec4>& ids, const ImageRGBA32F& test,
                                      const ImageRGBA32F& reference, bool interior) {
  std::map<uint32_t, Sums> sums;
  const int w = test.width, h = test.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint32_t id = ids[size_t(y * w + x)].x;
      if (interior) {
        bool same = x > 0 && y > 0 && x + 1 < w && y + 1 < h;
        for (int dy = -1; same && dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) same &= ids[size_t((y + dy) * w + x + dx)].x == id;
        if (!same) continue;
      }
      Sums& s = sums[id];
      s.hybrid += luminance(glm::vec3(test.at(x, y)));
      s.reference += luminance(glm::vec3(reference.at(x, y)));
      ++s.pixels;
    }
  return sums;
}

double meanLuminance(const ImageRGBA32F& image) {
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += luminance(glm::vec3(image.at(x, y)));
  return sum / double(std::max<size_t>(image.pixelCount(), 1));
}

// The pixels of one instance that differ most: luminance of test and reference.
void printInstancePixels(const std::vector<glm::uvec4>& ids, uint32_t instance,
                         const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  struct P {
    int x, y;
    double t, r;
  };
  std::vector<P> pixels;
  double sumT = 0.0, sumR = 0.0;
  for (int y = 0; y < test.height; ++y)
    for (int x = 0; x < test.width; ++x)
      if (ids[size_t(y * test.width + x)].x == instance) {
        P p{x, y, luminance(glm::vec3(test.at(x, y))), luminance(glm::vec3(reference.at(x, y)))};
        sumT += p.t, sumR += p.r;
        pixels.push_back(p);
      }
  std::sort(pixels.begin(), pixels.end(),
            [](const P& a, const P& b) { return std::abs(a.t - a.r) > std::abs(b.t - b.r); });
  std::printf("  instance %u: %zu pixels, sum %.1f vs %.1f; largest differences:", instance,
              pixels.size(), sumT, sumR);
  for (size_t i = 0; i < std::min<size_t>(pixels.size(), 10); ++i)
    std::printf(" (%d,%d) %.1f vs %.1f", pixels[i].x, pixels[i].y, pixels[i].t, pixels[i].r);
  std::printf("\n");
}

// The `count` pixels that contribute most to relMSE(test, reference): position, instance, share
// of relMSE, luminance of both.
void printWorstPixels(const std::vector<glm::uvec4>& ids, const ImageRGBA32F& test,
                      const ImageRGBA32F& reference, size_t count) {
  std::vector<std::pair<double, size_t>> errors;
  for (size_t i = 0; i < test.pixelCount(); ++i) {
    double e = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      const double r = reference.pixels[4 * i + c], d = test.pixels[4 * i + c] - r;
      e += d * d / (r * r + kRelMseEpsilon) / 3.0;
    }
    errors.push_back({e / double(test.pixelCount()), i});
  }
  count = std::min(count, errors.size());
  std::partial_sort(errors.begin(), errors.begin() + long(count), errors.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  std::printf("  largest shares of relMSE:");
  for (size_t k = 0; k < count; ++k) {
    const size_t i = errors[k].second;
    const int x = int(i % size_t(test.width)), y = int(i / size_t(test.width));
    std::printf(" (%d,%d id %u) %.4f [%.1f vs %.1f]", x, y, ids.empty() ? 0u : ids[i].x,
                errors[k].first, luminance(glm::vec3(test.at(x, y))),
                luminance(glm::vec3(reference.at(x, y))));
  }
  std::printf("\n");
}

// The instance index of sphere (row, column), -1 if the scene has none.
int sphereInstance(const Scene& scene, int row, int column) {
  const std::string name = fmt::format("sphere_{}_{}", row, column);
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].name == name) return int(i);
  return -1;
}

// The table: per sphere composite / reference, per row and column the pixel-weighted ratio.
void printSphereTable(const Scene& scene, const std::map<uint32_t, Sums>& sums, const char* what) {
  std::printf("  %-22s", what);
  for (int c = 0; c < kSpheresColumns; ++c) std::printf("  r%.2f", kSpheresRoughness[size_t(c)]);
  std::printf("    row   (reference)\n");
  std::vector<Sums> columns(kSpheresColumns);
  Sums metals;
  for (int r = 0; r < kSpheresRows; ++r) {
    Sums row;
    std::printf("  row %d %-16s", r,
                r < procedural::kSpheresMetalRows ? "(metal)" : "(dielectric)");
    for (int c = 0; c < kSpheresColumns; ++c) {
      int instance = sphereInstance(scene, r, c);
      auto it = instance < 0 ? sums.end() : sums.find(uint32_t(instance));
      Sums s = it == sums.end() ? Sums{} : it->second;
      std::printf("  %.3f", s.ratio());
      row.add(s);
      columns[size_t(c)].add(s);
      if (r < procedural::kSpheresMetalRows) metals.add(s);
    }
    std::printf("   %.3f  (%.3f)\n", row.ratio(), row.reference / std::max(row.pixels, 1));
  }
  std::printf("  %-22s", "columns");
  for (const Sums& c : columns) std::printf("  %.3f", c.ratio());
  std::printf("   metals %.3f\n", metals.ratio());
  std::printf("  others:");
  for (const auto& [instance, s] : sums)
    if (instance < scene.instances.size() &&
        scene.instances[instance].name.rfind("sphere_", 0) != 0 && s.pixels > 0)
      std::printf(" %s %.3f (%.3f, %d px)", scene.instances[instance].name.c_str(), s.ratio(),
                  s.reference / s.pixels, s.pixels);
  std::printf("\n");
}

struct Setup {
  explicit Setup(const Options& o) : options(o), size(parseResolution(o.resolution)) {
    scene = loadScene(o.scene);
    SceneOverrides overrides;
    if (!o.sun.empty()) overrides.sun = parseSun(o.sun);
    if (!o.sky.empty()) overrides.sky = parseSky(o.sky);
    applyOverrides(scene, overrides);
    if (o.noSun) scene.sun.irradiance = 0.0f;
    camera = effectiveCamera(scene);
  }

  // Cached per scene, lighting, size and samples.
  ImageRGBA32F reference(vk::Context& context, GpuScene& gpuScene) {
    const std::string key = std::to_string(std::hash<std::string>{}(
        options.scene + "|" + options.sun + "|" + options.sky + "|" +
        (options.noSun ? "nosun" : "") + (options.lambert ? "lambert" : "") + options.resolution +
        "|" + std::to_string(options.spp) + "|" + std::to_string(options.maxBounces) + "|" +
        std::to_string(options.seed)));
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("specular-diag-ref-" + key + ".exr");
    if (std::filesystem::exists(path)) return readImage(path.string());
    ReferencePathTracer tracer(context, gpuScene, scene);
    ReferenceOptions ro;
    ro.width = size.width;
    ro.height = size.height;
    ro.samplesPerPixel = options.spp;
    ro.pixelCentre = true;
    ro.lambert = options.lambert;
    ro.maxBounces = options.maxBounces;
    ro.seed = options.seed;
    ImageRGBA32F image = tracer.render(camera, ro).image;
    writeImage(path.string(), image);
    return image;
  }

  Options options;
  Resolution size;
  Scene scene;
  Camera camera;
};

int run(const Options& o) {
  Setup setup(o);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, setup.scene);
  const ImageRGBA32F reference = setup.reference(context, gpuScene);
  const uint32_t w = setup.size.width, h = setup.size.height;
  const std::vector<std::string> views = splitList(o.views, ',');
  if (!o.testImage.empty()) {  // a saved composite against the reference, nothing rendered
    const ImageRGBA32F test = readImage(o.testImage);
    std::printf("%s: relMSE %.4f, mean ratio %.4f (reference %u spp)\n", o.testImage.c_str(),
                relativeMeanSquaredError(test, reference),
                meanLuminance(test) / meanLuminance(reference), o.spp);
    printWorstPixels({}, test, reference, 12);
    return 0;
  }
  for (const std::string& name : splitList(o.configs, ',')) {
    HybridSettings settings = configurationSettings(name, w, h);
    settings.lambert = o.lambert;
    HybridFrame frame(context, gpuScene, setup.scene, settings);
    frame.requestDebugView("composite");
    frame.requestDebugView("vbuffer.ids");
    for (const std::string& v : views) frame.requestDebugView(v);
    ImageRGBA32F mean(w, h, glm::vec4(0.0f));
    std::vector<ImageRGBA32F> viewMeans;
    const int first = o.frames - o.averaged;
    for (int i = 0; i < o.frames; ++i) {
      frame.render(setup.camera);
      if (i < first) continue;
      ImageRGBA32F composite = frame.debugViewImage("composite");
      for (size_t k = 0; k < mean.pixels.size(); ++k)
        mean.pixels[k] += composite.pixels[k] / float(o.averaged);
      for (size_t v = 0; v < views.size(); ++v) {
        ImageRGBA32F image = frame.debugViewImage(views[v]);
        if (viewMeans.size() <= v) viewMeans.emplace_back(image.width, image.height, glm::vec4(0));
        for (size_t k = 0; k < image.pixels.size(); ++k)
          viewMeans[v].pixels[k] += image.pixels[k] / float(o.averaged);
      }
    }
    const std::vector<glm::uvec4> ids = instanceIds(frame);
    std::printf("%s: relMSE %.4f, mean ratio %.4f (frames %d-%d, reference %u spp)\n", name.c_str(),
                relativeMeanSquaredError(mean, reference),
                meanLuminance(mean) / meanLuminance(reference), first + 1, o.frames, o.spp);
    printSphereTable(setup.scene, instanceSums(ids, mean, reference, o.interior), "composite/ref");
    printWorstPixels(ids, mean, reference, 12);
    if (!o.sphere.empty()) {
      int r = 0, c = 0;
      if (std::sscanf(o.sphere.c_str(), "%d,%d", &r, &c) != 2) fail("--sphere: expected R,C");
      int instance = sphereInstance(setup.scene, r, c);
      if (instance >= 0) printInstancePixels(ids, uint32_t(instance), mean, reference);
    }
    for (size_t v = 0; v < views.size(); ++v) {
      // A view at another resolution is compared pixel for pixel after nearest upsampling.
      ImageRGBA32F full(w, h, glm::vec4(0.0f));
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
          full.set(int(x), int(y),
                   viewMeans[v].at(int(x * uint32_t(viewMeans[v].width) / w),
                                   int(y * uint32_t(viewMeans[v].height) / h)));
      printSphereTable(setup.scene, instanceSums(ids, full, reference, o.interior),
                       (views[v] + "/ref").c_str());
    }
    if (!o.imagesDir.empty()) {
      std::filesystem::create_directories(o.imagesDir);
      writeImage(o.imagesDir + "/specular-" + name + ".exr", mean);
      writeImage(o.imagesDir + "/specular-reference.exr", reference);
    }
    std::fflush(stdout);
  }
  return context.validationErrorCount() == 0 ? 0 : 4;
}

}  // namespace
}  // namespace bounce

int main(int argc, char** argv) {
  bounce::Options o;
  CLI::App app{"specular-diag: spheres' composite against the reference per sphere"};
  app.add_option("--scene", o.scene, "Built-in scene or glTF path with spheres named sphere_R_C");
  app.add_option("--res", o.resolution, "Image size WxH");
  app.add_option(
      "--configs", o.configs,
      "Comma-separated configurations: '+'-joined parts none|cache|evolve, dN "
      "(reflection divisor), maxrX, mirrorX, regX, ambientX, full-mip, mobile, no-reuse, "
      "no-denoise, no-di");
  app.add_option("--sun", o.sun, "Sun override, as bounce render's --sun");
  app.add_option("--sky", o.sky, "Sky override, as bounce render's --sky");
  app.add_option("--frames", o.frames, "Frames per configuration")->check(CLI::Range(1, 100000));
  app.add_option("--averaged", o.averaged, "The last N frames are averaged")
      ->check(CLI::Range(1, 100000));
  app.add_option("--spp", o.spp, "Reference samples per pixel (cached in the temp directory)");
  app.add_option("--views", o.views, "Debug views whose per-sphere means are also printed");
  app.add_flag("--no-sun", o.noSun, "Switch the sun off (a daylight sky goes black with it)");
  app.add_flag("--lambert", o.lambert, "Every material Lambert, in the frame and the reference");
  app.add_option("--max-bounces", o.maxBounces, "The reference's scattering events per path");
  app.add_option("--seed", o.seed, "The reference's random seed");
  app.add_option("--sphere", o.sphere, "R,C: print that sphere's most different pixels");
  app.add_flag("--interior", o.interior, "Leave silhouette pixels out");
  app.add_option("--test-image", o.testImage,
                 "Compare this EXR (a saved composite) with the reference instead of rendering");
  app.add_option("--images", o.imagesDir, "Write the mean composite and the reference as EXR here");
  CLI11_PARSE(app, argc, argv);
  if (o.averaged > o.frames) {
    std::fprintf(stderr, "--averaged must not exceed --frames\n");
    return 1;
  }
  try {
    return bounce::run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
