// Packs a scene's material textures into 2D array images, one per (size class, encoding),
// because lavapipe 22.3 has no descriptor indexing (DESIGN.md §1): a shader picks the array by
// the texture reference's size class and encoding and the layer by its low bits (the encoding
// of references is in shaders/shared/scene_layout.h). Also fills the GPU materials, and offers
// CPU samplers that mirror the GPU's alpha test, for the BVH builder and for tests.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shared/scene_layout.h"

namespace bounce {

// Every texture of one (size class, encoding): `layers` square RGBA8 images of side
// 64 << sizeClass, each with a full mip chain down to 1x1 (mipCount = log2(side) + 1).
//
// `texels` is mip-major: mip 0 of layer 0, mip 0 of layer 1, ..., then mip 1 of every layer,
// and so on. Each (layer, mip) image is (side >> mip)^2 texels, rows top to bottom (glTF UV
// (0,0) is the first texel), 4 bytes R, G, B, A. Mip-major is what one Vulkan buffer-to-image
// copy region per mip reads (all layers of a mip from consecutive memory). For sRGB arrays the
// RGB bytes are sRGB-encoded (upload as *_SRGB); alpha is always linear.
struct PackedTextureArray {
  uint32_t sizeClass = 0;
  bool srgb = false;
  uint32_t side = 0;
  uint32_t mipCount = 0;
  uint32_t layers = 0;
  std::vector<uint8_t> texels;

  uint32_t mipSide(uint32_t mip) const { return side >> mip; }
  // Bytes of one layer at `mip`.
  size_t layerBytes(uint32_t mip) const { return size_t(mipSide(mip)) * mipSide(mip) * 4; }
  // Byte offset of (layer 0, mip) in `texels`; every layer of that mip follows it.
  size_t mipOffset(uint32_t mip) const;
  // Byte offset of texel (x, y) of `layer` at `mip`.
  size_t texelOffset(uint32_t layer, uint32_t mip, uint32_t x, uint32_t y) const;
};

struct PackedTextures {
  std::vector<PackedTextureArray> arrays;   // only non-empty ones, ordered by (class, sRGB)
  std::vector<gpu::GpuMaterial> materials;  // one per Scene::materials entry, same order

  // The array holding (sizeClass, srgb) textures, or nullptr when there is none.
  const PackedTextureArray* find(uint32_t sizeClass, bool srgb) const;
};

// Packs every (image, encoding) pair a material uses: base colour and emissive as sRGB, metallic-
// roughness and normal maps as linear (an image used both ways is packed twice). Each is
// resampled (bilinear, wrapping like the GPU's repeat sampler, non-square images stretched) to
// a square power-of-two side = next power of two of max(width, height), clamped to [64, 2048],
// and gets a box-filtered mip chain; sRGB images are filtered in linear space. Throws
// bounce::Error if a (class, encoding) needs more layers than a reference can address.
PackedTextures packSceneTextures(const Scene& scene);

// Texture references (see scene_layout.h): layer in bits 0-15, size class in 16-19, sRGB bit 20.
uint32_t makeTextureRef(uint32_t layer, uint32_t sizeClass, bool srgb);
inline uint32_t textureRefLayer(uint32_t ref) {
  return ref & 0xFFFFu;
}
inline uint32_t textureRefSizeClass(uint32_t ref) {
  return (ref >> 16) & 0xFu;
}
inline bool textureRefIsSrgb(uint32_t ref) {
  return (ref & gpu::TEXTURE_SRGB_BIT) != 0;
}

// Nearest-texel lookups at mip 0 with repeat wrapping, as the GPU alpha test does: texel =
// floor(fract(uv) * side), clamped to [0, side - 1]. NO_TEXTURE reads as opaque white.
// Non-finite UVs read texel (0, 0). A reference to a missing array or layer throws
// bounce::Error.
glm::vec4 sampleTexelNearest(const PackedTextures& textures, uint32_t textureRef, glm::vec2 uv);
// Alpha in [0, 1] of the texel sampleTexelNearest would read.
float sampleAlphaNearest(const PackedTextures& textures, uint32_t textureRef, glm::vec2 uv);
// The alpha the alpha test compares with alphaCutoff: baseColor.a x base colour texture alpha.
float materialAlpha(const PackedTextures& textures, const gpu::GpuMaterial& material, glm::vec2 uv);

// The sRGB transfer functions the packer uses (IEC 61966-2-1). linearToSrgb8 rounds to the
// nearest code in sRGB space and is the exact inverse of srgb8ToLinear on every code.
float srgb8ToLinear(uint8_t code);
uint8_t linearToSrgb8(float linear);

}  // namespace bounce
