#include "di/di_debug_views.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/error.h"
#include "di/di_pass.h"
#include "shared/restir_di_io.h"

namespace bounce {

namespace {

// A colour per light index: the index hashed to a hue-like RGB in [0.2, 1].
void lightColour(float light, float* rgb) {
  if (light < 0.0f) {
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    return;
  }
  uint32_t h = uint32_t(light) * 0x9E3779B9u;
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  for (int c = 0; c < 3; ++c) rgb[c] = 0.2f + 0.8f * float((h >> (8 * c)) & 0xFFu) / 255.0f;
}

}  // namespace

std::vector<std::string> diDerivedViewNames() {
  return {"di.light", "di.m", "di.w", "di.visibility"};
}

bool isDiDerivedView(const std::string& name) {
  const std::vector<std::string> names = diDerivedViewNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

ImageRGBA32F diDerivedView(const std::string& name, const ImageRGBA32F& info) {
  if (!isDiDerivedView(name)) fail("DI debug view '{}': unknown", name);
  // The channel shown, and the scale that makes a PNG readable: M over the image's largest M;
  // W over four times its mean where positive (W's range is wide; the EXR of
  // di.reservoir-info keeps the values).
  const int channel = name == "di.m" ? 1 : name == "di.w" ? 2 : 3;
  double largest = 0.0, sum = 0.0;
  size_t positive = 0;
  for (size_t i = 0; i < info.pixelCount(); ++i) {
    const float v = info.pixels[4 * i + size_t(channel)];
    largest = std::max(largest, double(v));
    if (v > 0.0f) sum += v, ++positive;
  }
  double scale = 1.0;
  if (name == "di.m" && largest > 0.0) scale = 1.0 / largest;
  if (name == "di.w" && sum > 0.0) scale = double(positive) / (4.0 * sum);
  ImageRGBA32F out = info;
  for (size_t i = 0; i < info.pixelCount(); ++i) {
    const float* in = &info.pixels[4 * i];
    float* o = &out.pixels[4 * i];
    if (name == "di.light") {
      lightColour(in[0], o);
    } else {
      float v = in[channel];
      if (name == "di.visibility")
        v = v < 0.0f ? 0.25f : v;
      else
        v = float(std::min(1.0, double(v) * scale));
      o[0] = o[1] = o[2] = v;
    }
    o[3] = 1.0f;
  }
  return out;
}

bool isDiReservoirView(const graph::DebugView& view) {
  return view.isImage && view.format == kDiReservoirFormat &&
         (view.resource == "di.candidate" || view.resource == "di.reservoir" ||
          view.resource == "di.spatial" || view.resource == "di.reservoir-final");
}

ImageRGBA32F decodeDiReservoirView(const graph::DebugView& view) {
  ImageRGBA32F out(view.width, view.height);
  const size_t texels = size_t(view.width) * view.height;
  if (view.bytes.size() < texels * 16) fail("DI view '{}': too few bytes", view.name);
  for (size_t i = 0; i < texels; ++i) {
    uint32_t t[4];
    std::memcpy(t, view.bytes.data() + 16 * i, sizeof(t));
    out.pixels[4 * i] = t[0] == gpu::DI_NO_LIGHT
                            ? -1.0f
                            : float(t[0] & ~(gpu::DI_LIGHT_DISTANT | gpu::DI_VISIBLE_AGE_MASK));
    out.pixels[4 * i + 1] = std::bit_cast<float>(t[3]);
    out.pixels[4 * i + 2] = std::bit_cast<float>(t[2]);
    out.pixels[4 * i + 3] = 0.0f;
  }
  return out;
}

}  // namespace bounce
