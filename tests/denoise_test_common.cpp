#include "denoise_test_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "graph/debug_view_image.h"
#include "harness.h"
#include "scene/load.h"
#include "scene/scene_options.h"

namespace bounce::test {

namespace {
constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
}  // namespace

double luminance(const glm::vec4& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

std::vector<uint8_t> floatBytes(std::span<const float> values) {
  std::vector<uint8_t> bytes(values.size() * 4);
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

std::vector<float> flatten(const std::vector<glm::vec4>& pixels) {
  std::vector<float> out;
  for (const glm::vec4& p : pixels) out.insert(out.end(), {p.x, p.y, p.z, p.w});
  return out;
}

std::vector<glm::vec4> pixelsOf(const ImageRGBA32F& image) {
  std::vector<glm::vec4> out(size_t(image.width) * size_t(image.height));
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = {image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2],
              image.pixels[4 * i + 3]};
  return out;
}

// ---- DenoiseRig --------------------------------------------------------------------------------

DenoiseRig::DenoiseRig(vk::Context& context, uint32_t width, uint32_t height)
    : context_(context),
      scene_(loadScene("cornell")),
      gpuScene_(context, scene_),
      width_(width),
      height_(height),
      noisy_(denoiseInputImage(context, kRgba16f, width, height, "test.noisy")),
      depth_(denoiseInputImage(context, VK_FORMAT_R32_SFLOAT, width, height, "test.depth")),
      normals_(denoiseInputImage(context, kRgba16f, width, height, "test.normals")),
      motion_(denoiseInputImage(context, VK_FORMAT_R16G16_SFLOAT, width, height, "test.motion")) {}

std::vector<glm::vec4> DenoiseRig::frame(const DenoiseFrame& f, const Declare& declare) {
  vk::uploadImage(context_, noisy_, halfBytes(flatten(f.noisy)), 8);
  vk::uploadImage(context_, depth_, floatBytes(f.depth), 4);
  vk::uploadImage(context_, normals_, halfBytes(flatten(f.normals)), 8);
  std::vector<float> motion;
  for (const glm::vec2& m : f.motion) motion.insert(motion.end(), {m.x, m.y});
  vk::uploadImage(context_, motion_, halfBytes(motion), 4);
  graph::FrameGraph& graph = beginFrame("test.output");
  DenoiseInputs in{import("test.noisy", noisy_), import("test.depth", depth_),
                   import("test.normals", normals_), import("test.motion", motion_)};
  declare(graph, in, graph.createImage("test.output", {kRgba16f}));
  return run("test.output");
}

graph::FrameGraph& DenoiseRig::beginFrame(const std::string& view) {
  graph_.beginFrame();
  graph_.requestDebugView(view);
  for (const std::string& name : views_) graph_.requestDebugView(name);
  return graph_;
}

std::vector<glm::vec4> DenoiseRig::view(const std::string& name) {
  return pixelsOf(graph::debugViewImage(graph_.readDebugView(name)));
}

graph::ImageHandle DenoiseRig::import(const std::string& name, vk::Image& image) {
  graph::ImportedImage imported =
      graph::ImportedImage::from(image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  imported.externalWrites = true;  // uploaded again between frames
  return graph_.importImage(name, imported);
}

std::vector<glm::vec4> DenoiseRig::run(const std::string& view) {
  graph_.allocate(context_, {width_, height_});
  context_.submitAndWait([&](VkCommandBuffer cmd) { graph_.execute(cmd); });
  return pixelsOf(graph::debugViewImage(graph_.readDebugView(view)));
}

// ---- statistics --------------------------------------------------------------------------------

std::vector<bool> besideDepthEdge(const std::vector<float>& depth, uint32_t w, uint32_t h) {
  std::vector<bool> edge(depth.size(), false);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      float z = depth[y * w + x];
      if (!(z > 0.0f)) continue;
      const int offsets[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const auto& o : offsets) {
        int qx = int(x) + o[0], qy = int(y) + o[1];
        if (qx < 0 || qy < 0 || qx >= int(w) || qy >= int(h)) continue;
        float zq = depth[size_t(qy) * w + size_t(qx)];
        if (zq > 0.0f && std::abs(zq - z) > 0.1f * z) edge[y * w + x] = true;
      }
    }
  return edge;
}

Gates measure(const std::vector<glm::vec4>& noisy, const std::vector<glm::vec4>& denoised,
              const std::vector<glm::vec4>& truth, const std::vector<float>& depth, uint32_t w,
              uint32_t h) {
  const std::vector<bool> edge = besideDepthEdge(depth, w, h);
  Gates g;
  size_t n = 0, rest = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    for (int c = 0; c < 3; ++c) g.nonFinite += std::isfinite(denoised[i][c]) ? 0 : 1;
    if (!(depth[i] > 0.0f)) continue;
    double t = luminance(truth[i]), in = luminance(noisy[i]), out = luminance(denoised[i]);
    g.meanTrue += t;
    g.meanIn += in;
    g.meanOut += out;
    g.varianceIn += (in - t) * (in - t);
    g.varianceOut += (out - t) * (out - t);
    (edge[i] ? g.edgeError : g.restError) += std::abs(out - t);
    (edge[i] ? g.edgePixels : rest) += 1;
    ++n;
  }
  g.meanTrue /= double(n);
  g.meanIn /= double(n);
  g.meanOut /= double(n);
  g.varianceIn /= double(n);
  g.varianceOut /= double(n);
  g.edgeError /= double(std::max<size_t>(g.edgePixels, 1));
  g.restError /= double(std::max<size_t>(rest, 1));
  return g;
}

double weightedMean(const std::vector<std::vector<glm::vec4>>& frames,
                    const std::vector<float>& depth, float alpha) {
  double mean = 0.0;
  for (size_t k = 0; k < frames.size(); ++k) {
    double frameMean = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < depth.size(); ++i)
      if (depth[i] > 0.0f) {
        frameMean += luminance(frames[k][i]);
        ++n;
      }
    double a = std::max(double(alpha), 1.0 / double(k + 1));
    mean = (1.0 - a) * mean + a * frameMean / double(n);
  }
  return mean;
}

void print(const std::string& what, const Gates& g) {
  std::printf(
      "%s: mean %.4f (noisy %.4f, known %.4f: %+.2f %%; inputs %.4f: %+.2f %%), squared error "
      "%.3g -> %.3g (%.1fx lower), |error| beside %zu depth-edge pixels %.4f vs %.4f elsewhere "
      "(%.2fx), %zu non-finite\n",
      what.c_str(), g.meanOut, g.meanIn, g.meanTrue, 100.0 * (g.meanOut / g.meanTrue - 1.0),
      g.meanSeen, 100.0 * (g.meanOut / g.meanSeen - 1.0), g.varianceIn, g.varianceOut,
      g.varianceIn / g.varianceOut, g.edgePixels, g.edgeError, g.restError,
      g.edgeError / g.restError, g.nonFinite);
}

void expectMeanKept(const Gates& g, bool known) {
  EXPECT_NEAR(g.meanOut / (known ? g.meanTrue : g.meanSeen), 1.0, 0.02);
}
void expectVarianceLower(const Gates& g) {
  EXPECT_GE(g.varianceIn / g.varianceOut, 4.0);
}
void expectEdgesKept(const Gates& g) {
  ASSERT_GT(g.edgePixels, 0u);
  EXPECT_LE(g.edgeError, 1.5 * g.restError);
}

void writeStrip(const std::string& tag, const std::string& name, uint32_t w, uint32_t h,
                const std::vector<std::vector<glm::vec4>>& images) {
  constexpr uint32_t zoom = 4;
  ImageRGBA32F strip;
  strip.width = int(w * zoom * images.size());
  strip.height = int(h * zoom);
  strip.pixels.assign(size_t(strip.width) * strip.height * 4, 0.0f);
  for (size_t k = 0; k < images.size(); ++k)
    for (uint32_t y = 0; y < h * zoom; ++y)
      for (uint32_t x = 0; x < w * zoom; ++x)
        for (int c = 0; c < 3; ++c)
          strip.pixels[(size_t(y) * strip.width + k * w * zoom + x) * 4 + c] =
              images[k][(y / zoom) * w + x / zoom][c];
  for (size_t i = 3; i < strip.pixels.size(); i += 4) strip.pixels[i] = 1.0f;
  static std::map<std::string, std::string> dirs;  // tempDir empties the directory: once a tag
  auto [it, fresh] = dirs.try_emplace(tag);
  if (fresh) it->second = tempDir(tag);
  std::string path = it->second + "/" + name + ".png";
  writePng(path, strip);
  std::printf("wrote %s\n", path.c_str());
}

// ---- inputs ------------------------------------------------------------------------------------

Gates twoPlanesGates(const DenoiseStep& denoise, float alpha, int shift, const std::string& tag,
                     const std::string& name) {
  constexpr uint32_t w = kTwoPlanesWidth, h = kTwoPlanesHeight;
  std::mt19937 rng(3);
  std::exponential_distribution<float> noise(1.0f);
  std::vector<glm::vec4> out, truth;
  std::vector<std::vector<glm::vec4>> inputs;
  DenoiseFrame f;
  for (int frame = 0; frame < 16; ++frame) {
    f = DenoiseFrame{};
    truth.clear();
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        int world = ((int(x) - shift * frame) % int(w) + int(w)) % int(w);
        bool near = world < int(w) / 2;
        f.depth.push_back(near ? 2.0f : 6.0f);
        f.normals.push_back({0.0f, 0.0f, 1.0f, 0.0f});
        f.motion.push_back({float(shift), 0.0f});
        float m = near ? 1.0f : 0.25f;
        truth.push_back({m, m, m, 1.0f});
      }
    for (const glm::vec4& t : truth) f.noisy.push_back(t * noise(rng));
    inputs.push_back(f.noisy);
    out = denoise(f);
  }
  Gates g = measure(f.noisy, out, truth, f.depth, w, h);
  g.meanSeen = weightedMean(inputs, f.depth, alpha);
  print(name + ", 16 frames", g);
  writeStrip(tag, name, w, h, {f.noisy, out, truth});
  return g;
}

GiSamples giSamples(vk::Context& context, const std::string& sceneName, uint32_t w, uint32_t h,
                    int count) {
  Scene scene = loadScene(sceneName);
  GpuScene gpuScene(context, scene);
  HybridSettings s = presetSettings(Preset::Desktop);
  s.width = w;
  s.height = h;
  s.lambert = true;
  s.gi = GiMode::Evolve;
  s.restirGi.denoiser = GiDenoiser::None;
  HybridFrame frame(context, gpuScene, scene, s);
  for (const char* view : {"gi.diffuse", "gbuffer.depth", "gbuffer.normals"})
    frame.requestDebugView(view);
  GiSamples out{w, h, {}, {}};
  for (int i = 0; i < count; ++i) {
    frame.resetHistory();
    frame.render(effectiveCamera(scene));
    out.frames.push_back(pixelsOf(frame.debugViewImage("gi.diffuse")));
  }
  ImageRGBA32F depth = frame.debugViewImage("gbuffer.depth");
  ImageRGBA32F normals = frame.debugViewImage("gbuffer.normals");
  for (uint32_t i = 0; i < w * h; ++i) {
    out.surface.depth.push_back(depth.pixels[4 * i]);
    glm::vec3 n = decodeOctahedral({normals.pixels[4 * i], normals.pixels[4 * i + 1]});
    out.surface.normals.push_back({n, 0.0f});
    out.surface.motion.push_back({0.0f, 0.0f});
  }
  return out;
}

Gates giGates(const GiSamples& samples, const DenoiseStep& denoise, float alpha,
              const std::string& what, const std::string& tag, const std::string& name) {
  const uint32_t w = samples.width, h = samples.height;
  std::vector<glm::vec4> truth(size_t(w) * h, glm::vec4(0.0f));
  for (int k = 0; k < kGiMeanFrames; ++k)
    for (size_t i = 0; i < truth.size(); ++i)
      truth[i] += samples.frames[k][i] / float(kGiMeanFrames);
  DenoiseFrame f = samples.surface;
  std::vector<glm::vec4> out;
  for (int k = 0; k < kGiDenoisedFrames; ++k) {
    f.noisy = samples.frames[kGiMeanFrames + k];
    out = denoise(f);
  }
  Gates g = measure(f.noisy, out, truth, f.depth, w, h);
  g.meanSeen = weightedMean(std::vector<std::vector<glm::vec4>>(
                                samples.frames.begin() + kGiMeanFrames,
                                samples.frames.begin() + kGiMeanFrames + kGiDenoisedFrames),
                            f.depth, alpha);
  print(what + " GI at 1 frame, 16 frames", g);
  writeStrip(tag, name, w, h, {f.noisy, out, truth});
  return g;
}

}  // namespace bounce::test
