#include "tools/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <stb_image_write.h>

#include "core/error.h"
#include "tools/flip.h"
#include "tools/image_io.h"

namespace bounce {
namespace {

constexpr int kTableSize = 256;

// OKLab -> linear sRGB (Ottosson 2020, "A perceptual color space for image processing").
glm::vec3 oklabToLinearSrgb(const glm::vec3& lab) {
  const float l = lab.x + 0.3963377774f * lab.y + 0.2158037573f * lab.z;
  const float m = lab.x - 0.1055613458f * lab.y - 0.0638541728f * lab.z;
  const float s = lab.x - 0.0894841775f * lab.y - 1.2914855480f * lab.z;
  const float l3 = l * l * l, m3 = m * m * m, s3 = s * s * s;
  return {4.0767416621f * l3 - 3.3077115913f * m3 + 0.2309699292f * s3,
          -1.2684380046f * l3 + 2.6097574011f * m3 - 0.3413193965f * s3,
          -0.0041960863f * l3 - 0.7034186147f * m3 + 1.7076147010f * s3};
}

bool inGamut(const glm::vec3& rgb) {
  constexpr float tolerance = 1e-4f;
  for (int c = 0; c < 3; ++c) {
    if (rgb[c] < -tolerance || rgb[c] > 1.0f + tolerance) return false;
  }
  return true;
}

glm::vec3 oklabFromLch(float lightness, float chroma, float hueDegrees) {
  const float h = hueDegrees * 3.14159265358979f / 180.0f;
  return {lightness, chroma * std::cos(h), chroma * std::sin(h)};
}

// The design of the ramp, in OKLCh: lightness 0.16 -> 0.97 linearly; hue 285 (violet) -> 460
// = 100 (yellow) through red (~30) and orange (~60); chroma peaks mid-ramp and fades at both
// ends, where the gamut is narrow.
glm::vec3 rampColor(float t) {
  const float lightness = 0.16f + 0.81f * t;
  const float hue = 285.0f + 175.0f * t;
  const float arch = std::max(0.0f, std::sin(3.14159265358979f * t));  // sin(pi) rounds below 0
  float chroma = 0.03f + 0.15f * std::pow(arch, 0.8f);
  // Largest in-gamut chroma up to the design value, by bisection (lightness and hue stay).
  if (!inGamut(oklabToLinearSrgb(oklabFromLch(lightness, chroma, hue)))) {
    float low = 0.0f, high = chroma;
    for (int i = 0; i < 24; ++i) {
      const float mid = 0.5f * (low + high);
      (inGamut(oklabToLinearSrgb(oklabFromLch(lightness, mid, hue))) ? low : high) = mid;
    }
    chroma = low;
  }
  const glm::vec3 linear = oklabToLinearSrgb(oklabFromLch(lightness, chroma, hue));
  glm::vec3 encoded;
  for (int c = 0; c < 3; ++c) encoded[c] = linearToSrgb(std::clamp(linear[c], 0.0f, 1.0f));
  return encoded;
}

const std::array<glm::vec3, kTableSize>& heatmapTable() {
  static const std::array<glm::vec3, kTableSize> table = [] {
    std::array<glm::vec3, kTableSize> t{};
    for (int i = 0; i < kTableSize; ++i) t[i] = rampColor(float(i) / float(kTableSize - 1));
    return t;
  }();
  return table;
}

}  // namespace

glm::vec3 heatmapColor(float t) {
  const float clamped = t > 0.0f ? std::min(t, 1.0f) : 0.0f;
  return heatmapTable()[size_t(std::lround(clamped * (kTableSize - 1)))];
}

void writeHeatmap(const std::string& path, const std::vector<float>& errorMap, int width,
                  int height) {
  if (width <= 0 || height <= 0 || errorMap.size() != size_t(width) * size_t(height)) {
    fail("{}: heat map of {} values cannot be {}x{}", path, errorMap.size(), width, height);
  }
  std::vector<uint8_t> bytes(errorMap.size() * 3);
  for (size_t i = 0; i < errorMap.size(); ++i) {
    const glm::vec3 color = heatmapColor(errorMap[i]);
    for (int c = 0; c < 3; ++c) bytes[3 * i + c] = uint8_t(std::lround(color[c] * 255.0f));
  }
  if (!stbi_write_png(path.c_str(), width, height, 3, bytes.data(), width * 3)) {
    fail("{}: cannot write PNG (does the directory exist and is it writable?)", path);
  }
}

void writeHeatmap(const std::string& path, const FlipResult& flip) {
  writeHeatmap(path, flip.errorMap, flip.width, flip.height);
}

}  // namespace bounce
