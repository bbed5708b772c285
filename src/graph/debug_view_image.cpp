#include "graph/debug_view_image.h"

#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "core/error.h"

namespace bounce::graph {

namespace {

template <typename T>
T load(const std::byte* texel, size_t component) {
  T value;
  std::memcpy(&value, texel + component * sizeof(T), sizeof(T));
  return value;
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// A colour per id, so that neighbouring ids differ visibly: the id hashed (a 32-bit integer
// mix), three bytes of the hash as sRGB. 0xFFFFFFFF (no id) is black.
glm::vec4 idColor(uint32_t id) {
  if (id == 0xFFFFFFFFu) return {0.0f, 0.0f, 0.0f, 1.0f};
  uint32_t h = id * 0x9E3779B1u;
  h ^= h >> 15;
  h *= 0x85EBCA77u;
  h ^= h >> 13;
  auto channel = [&](int shift) {
    return srgbToLinear(0.25f + 0.75f * float((h >> shift) & 255u) / 255.0f);
  };
  return {channel(0), channel(8), channel(16), 1.0f};
}

// Red, green, blue, alpha of one texel; channels a format lacks read as 0 (alpha as 1).
glm::vec4 decodeTexel(VkFormat format, const std::byte* t) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: {
      float v = load<float>(t, 0);
      return {v, v, v, 1.0f};
    }
    case VK_FORMAT_R32_UINT: {
      float v = float(load<uint32_t>(t, 0));
      return {v, v, v, 1.0f};
    }
    case VK_FORMAT_R32G32_SFLOAT:
      return {load<float>(t, 0), load<float>(t, 1), 0.0f, 1.0f};
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return {load<float>(t, 0), load<float>(t, 1), load<float>(t, 2), load<float>(t, 3)};
    case VK_FORMAT_R16_SFLOAT: {
      float v = glm::unpackHalf1x16(load<uint16_t>(t, 0));
      return {v, v, v, 1.0f};
    }
    case VK_FORMAT_R16G16_SFLOAT:
      return {glm::unpackHalf1x16(load<uint16_t>(t, 0)), glm::unpackHalf1x16(load<uint16_t>(t, 1)),
              0.0f, 1.0f};
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return {glm::unpackHalf1x16(load<uint16_t>(t, 0)), glm::unpackHalf1x16(load<uint16_t>(t, 1)),
              glm::unpackHalf1x16(load<uint16_t>(t, 2)), glm::unpackHalf1x16(load<uint16_t>(t, 3))};
    case VK_FORMAT_R8G8B8A8_UNORM:
      return glm::vec4(float(load<uint8_t>(t, 0)), float(load<uint8_t>(t, 1)),
                       float(load<uint8_t>(t, 2)), float(load<uint8_t>(t, 3))) /
             255.0f;
    case VK_FORMAT_R32G32B32A32_UINT: {  // ids (vbuffer: instance, geometry, primitive)
      uint32_t first = load<uint32_t>(t, 0);
      if (first == 0xFFFFFFFFu) return idColor(first);
      return idColor(first * 0x01000193u ^ load<uint32_t>(t, 1) * 0x27D4EB2Du ^
                     load<uint32_t>(t, 2));
    }
    case VK_FORMAT_R8G8B8A8_SRGB: {
      glm::vec4 c = decodeTexel(VK_FORMAT_R8G8B8A8_UNORM, t);
      return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z), c.w};
    }
    default:
      fail("debug view: VkFormat {} cannot be shown as an image", int(format));
  }
}

}  // namespace

ImageRGBA32F debugViewImage(const DebugView& view) {
  if (!view.isImage)
    fail("debug view '{}': '{}' is a buffer, not an image", view.name, view.resource);
  uint32_t texelBytes = bytesPerTexel(view.format);
  if (texelBytes == 0)
    fail("debug view '{}': VkFormat {} cannot be shown as an image", view.name, int(view.format));
  if (view.bytes.size() < size_t(view.width) * view.height * texelBytes)
    fail("debug view '{}': {} bytes for a {}x{} image", view.name, view.bytes.size(), view.width,
         view.height);
  ImageRGBA32F image(int(view.width), int(view.height));
  try {
    for (uint32_t y = 0; y < view.height; ++y)
      for (uint32_t x = 0; x < view.width; ++x) {
        const std::byte* texel = view.bytes.data() + (size_t(y) * view.width + x) * texelBytes;
        image.set(int(x), int(y), decodeTexel(view.format, texel));
      }
  } catch (const Error& e) {
    fail("debug view '{}': {}", view.name, e.what());
  }
  return image;
}

}  // namespace bounce::graph
