// A denoiser alone (bounce/denoiser.h): no renderer, no scene. The host makes a noisy signal of
// known mean on its own G-buffer (a wall and a nearer box in front of it, lit by a smooth
// gradient, every pixel's value the mean times exponential noise, as Monte Carlo noise is
// skewed), feeds 16 frames of it with the box moving right, and writes the last noisy frame
// and the denoised one side by side. It prints the RMS error against the known mean before and
// after.
//
//   bounce_example_denoise [svgf|reblur|hybrid] [out.png]
#include <cmath>
#include <cstdio>
#include <exception>
#include <random>
#include <string>

#include <bounce/bounce.h>

namespace {

constexpr uint32_t kWidth = 160, kHeight = 96;

struct Scene {
  int boxLeft = 0;  // the box: 40x40 pixels from (boxLeft, 28)
  bool inBox(uint32_t x, uint32_t y) const {
    return int(x) >= boxLeft && int(x) < boxLeft + 40 && y >= 28 && y < 68;
  }
  float mean(uint32_t x, uint32_t y) const {
    return inBox(x, y) ? 0.9f : 0.2f + 0.6f * float(x) / float(kWidth);
  }
};

// One frame of the host's G-buffer and noisy signal.
bounce::DenoiserFrame makeFrame(const Scene& scene, int moved, std::mt19937& rng) {
  std::exponential_distribution<float> noise(1.0f);
  bounce::DenoiserFrame f;
  f.noisy = {kWidth, kHeight, std::vector<float>(kWidth * kHeight * 4)};
  f.normal = {kWidth, kHeight, std::vector<float>(kWidth * kHeight * 4)};
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      const bool box = scene.inBox(x, y);
      f.depth.push_back(box ? 2.0f : 5.0f);  // view depth: any unit
      f.motion.push_back(box ? float(moved) : 0.0f);
      f.motion.push_back(0.0f);
      const float v = scene.mean(x, y) * noise(rng);
      for (int c = 0; c < 3; ++c) f.noisy.rgba[4 * i + c] = v;
      f.normal.rgba[4 * i + 2] = 1.0f;  // facing the camera
    }
  return f;
}

double rmsError(const bounce::Image& image, const Scene& scene) {
  double sum = 0.0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      double d = image.pixel(x, y)[0] - scene.mean(x, y);
      sum += d * d;
    }
  return std::sqrt(sum / double(kWidth * kHeight));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const bounce::DenoiserKind kind = bounce::denoiserKindFromName(argc > 1 ? argv[1] : "reblur");
    bounce::Denoiser denoiser = bounce::Denoiser::create(kind, kWidth, kHeight);
    std::printf("%s: %u pipelines on %s\n", argc > 1 ? argv[1] : "reblur", denoiser.pipelineCount(),
                denoiser.deviceName().c_str());
    std::mt19937 rng(1);
    Scene scene;
    bounce::DenoiserFrame frame;
    bounce::Image denoised;
    for (int i = 0; i < 16; ++i) {
      const int moved = i == 0 ? 0 : 2;  // the box moves 2 pixels a frame
      scene.boxLeft = 20 + 2 * i;
      frame = makeFrame(scene, moved, rng);
      denoised = denoiser.denoise(frame);
    }
    const double before = rmsError(frame.noisy, scene), after = rmsError(denoised, scene);
    std::printf("RMS error against the known mean: noisy %.4f, denoised %.4f (%.1fx lower)\n",
                before, after, before / after);

    if (argc > 2) {
      bounce::Image strip{2 * kWidth, kHeight, std::vector<float>(2 * kWidth * kHeight * 4, 1.0f)};
      for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x)
          for (int c = 0; c < 3; ++c) {
            strip.rgba[4 * (size_t(y) * 2 * kWidth + x) + c] = frame.noisy.pixel(x, y)[c];
            strip.rgba[4 * (size_t(y) * 2 * kWidth + kWidth + x) + c] = denoised.pixel(x, y)[c];
          }
      bounce::writeImage(argv[2], strip);
      std::printf("wrote %s (noisy | denoised)\n", argv[2]);
    }
    return after < before ? 0 : 1;
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce_example_denoise: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce_example_denoise: unexpected error: %s\n", e.what());
  }
  return 1;
}
