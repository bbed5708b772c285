// Texture packing: size classes, mip chains (box filter, in linear space for sRGB), texture
// references, GPU materials, and the CPU nearest sampler that mirrors the GPU alpha test.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "harness.h"
#include "scene/load.h"
#include "scene/texture_pack.h"

namespace bounce {
namespace {

Image solidImage(int width, int height, glm::u8vec4 colour) {
  Image image;
  image.width = width;
  image.height = height;
  for (int i = 0; i < width * height; ++i)
    image.rgba.insert(image.rgba.end(), {colour.x, colour.y, colour.z, colour.w});
  return image;
}

// A per-texel checker of black and white, alpha 255.
Image checkerImage(int side) {
  Image image = solidImage(side, side, {0, 0, 0, 255});
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      if ((x + y) % 2)
        for (int c = 0; c < 3; ++c) image.rgba[size_t(y * side + x) * 4 + c] = 255;
  return image;
}

// Alpha that identifies its texel: (x + 3y) mod 256.
Image alphaRampImage(int side) {
  Image image = solidImage(side, side, {10, 20, 30, 0});
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      image.rgba[size_t(y * side + x) * 4 + 3] = uint8_t((x + 3 * y) % 256);
  return image;
}

Scene sceneWithBaseColour(Image image) {
  Scene scene;
  scene.images.push_back(std::move(image));
  Material m;
  m.baseColorTexture = 0;
  scene.materials.push_back(m);
  return scene;
}

glm::u8vec4 texel(const PackedTextureArray& a, uint32_t layer, uint32_t mip, uint32_t x,
                  uint32_t y) {
  const uint8_t* p = &a.texels[a.texelOffset(layer, mip, x, y)];
  return {p[0], p[1], p[2], p[3]};
}

TEST(TexturePack, NonSquareImageGoesToNextPowerOfTwoWithFullMipChain) {
  PackedTextures packed = packSceneTextures(sceneWithBaseColour(solidImage(100, 37, {1, 2, 3, 4})));
  ASSERT_EQ(packed.arrays.size(), 1u);
  const PackedTextureArray& a = packed.arrays[0];
  EXPECT_EQ(a.side, 128u);
  EXPECT_EQ(a.sizeClass, 1u);
  EXPECT_TRUE(a.srgb);
  EXPECT_EQ(a.layers, 1u);
  ASSERT_EQ(a.mipCount, 8u);  // 128, 64, ..., 1
  size_t bytes = 0;
  for (uint32_t mip = 0; mip < a.mipCount; ++mip) {
    EXPECT_EQ(a.mipSide(mip), 128u >> mip);
    bytes += size_t(a.mipSide(mip)) * a.mipSide(mip) * 4;
  }
  EXPECT_EQ(a.mipSide(a.mipCount - 1), 1u);
  EXPECT_EQ(a.texels.size(), bytes);
  ASSERT_EQ(packed.materials.size(), 1u);
  EXPECT_EQ(packed.materials[0].baseColorTexture, makeTextureRef(0, 1, true));
  EXPECT_EQ(packed.materials[0].normalTexture, gpu::NO_TEXTURE);
}

TEST(TexturePack, SizesClampTo64And2048) {
  Scene scene;
  scene.images = {solidImage(3, 5, {0, 0, 0, 255}), solidImage(2100, 1, {0, 0, 0, 255})};
  Material small, large;
  small.normalTexture = 0;
  large.normalTexture = 1;
  scene.materials = {small, large};
  PackedTextures packed = packSceneTextures(scene);
  ASSERT_EQ(packed.arrays.size(), 2u);
  EXPECT_EQ(packed.arrays[0].side, 64u);
  EXPECT_EQ(packed.arrays[1].side, 2048u);
  EXPECT_EQ(packed.arrays[1].mipCount, 12u);
  EXPECT_FALSE(packed.arrays[1].srgb);
  EXPECT_EQ(packed.materials[1].normalTexture, makeTextureRef(0, 5, false));
}

TEST(TexturePack, ConstantColourSurvivesEveryMip) {
  const glm::u8vec4 colour(200, 90, 31, 77);
  Scene scene;
  scene.images = {solidImage(100, 37, colour)};
  Material m;
  m.baseColorTexture = 0;          // sRGB
  m.metallicRoughnessTexture = 0;  // linear
  scene.materials = {m};
  PackedTextures packed = packSceneTextures(scene);
  ASSERT_EQ(packed.arrays.size(), 2u);  // the same image, packed once per encoding
  for (const PackedTextureArray& a : packed.arrays)
    for (uint32_t mip = 0; mip < a.mipCount; ++mip)
      for (uint32_t y = 0; y < a.mipSide(mip); ++y)
        for (uint32_t x = 0; x < a.mipSide(mip); ++x)
          ASSERT_EQ(texel(a, 0, mip, x, y), colour) << "srgb " << a.srgb << " mip " << mip;
}

// One image used by a material both as base colour (packed sRGB) and as normal map (linear).
PackedTextures packAsColourAndNormal(const Image& image) {
  Scene scene;
  scene.images = {image};
  Material m;
  m.baseColorTexture = 0;
  m.normalTexture = 0;
  scene.materials = {m};
  return packSceneTextures(scene);
}

// Averaging sRGB black and white must happen in linear space: linear 0.5 is sRGB code 188,
// not the 128 a naive byte average gives. Linear arrays average the bytes.
TEST(TexturePack, SrgbMipsFilterInLinearSpace) {
  PackedTextures packed = packAsColourAndNormal(checkerImage(64));
  const PackedTextureArray* srgb = packed.find(0, true);
  const PackedTextureArray* linear = packed.find(0, false);
  ASSERT_TRUE(srgb && linear);
  EXPECT_EQ(texel(*srgb, 0, 0, 1, 0), glm::u8vec4(255, 255, 255, 255));  // mip 0 untouched
  EXPECT_EQ(texel(*srgb, 0, 0, 0, 0), glm::u8vec4(0, 0, 0, 255));
  for (uint32_t mip = 1; mip < srgb->mipCount; ++mip) {
    EXPECT_EQ(texel(*srgb, 0, mip, 0, 0), glm::u8vec4(188, 188, 188, 255)) << "mip " << mip;
    EXPECT_EQ(texel(*linear, 0, mip, 0, 0), glm::u8vec4(128, 128, 128, 255)) << "mip " << mip;
  }
  EXPECT_NEAR(sampleTexelNearest(packed, packed.materials[0].baseColorTexture, {0.0f, 0.0f}).x,
              0.0f, 1e-6f);
  EXPECT_NEAR(sampleTexelNearest(packed, packed.materials[0].baseColorTexture, {1.5f / 64, 0.0f}).x,
              1.0f, 1e-6f);
}

// A cut-out texture: a checker of opaque green and fully transparent white texels. The colour
// of the transparent texels is never seen at mip 0, so a colour (sRGB) texture's coarser mips
// must stay green (coverage-weighted mean) with alpha the covered fraction, 0.5 (code 128);
// a plain mean would turn the leaf pale (linear 0.5 white + 0.5 green). Linear textures have
// no opacity in alpha and keep the plain mean.
TEST(TexturePack, ColourMipsIgnoreTransparentTexels) {
  const int side = 64;
  Image image = solidImage(side, side, {0, 0, 0, 0});
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      uint8_t* t = &image.rgba[size_t(y * side + x) * 4];
      bool opaque = (x + y) % 2 == 0;
      const uint8_t texelColour[4] = {uint8_t(opaque ? 40 : 255), 200, uint8_t(opaque ? 60 : 255),
                                      uint8_t(opaque ? 255 : 0)};
      std::copy(texelColour, texelColour + 4, t);
    }
  PackedTextures packed = packAsColourAndNormal(image);
  const PackedTextureArray* srgb = packed.find(0, true);
  const PackedTextureArray* linear = packed.find(0, false);
  ASSERT_TRUE(srgb && linear);
  for (uint32_t mip = 1; mip < srgb->mipCount; ++mip) {
    EXPECT_EQ(texel(*srgb, 0, mip, 0, 0), glm::u8vec4(40, 200, 60, 128)) << "mip " << mip;
    glm::u8vec4 plain = texel(*linear, 0, mip, 0, 0);
    EXPECT_EQ(plain.x, 148) << "mip " << mip;  // (40 + 255) / 2, rounded
    EXPECT_EQ(plain.w, 128) << "mip " << mip;
  }
}

TEST(TexturePack, AlphaSamplingWrapsAndPicksNearestTexel) {
  Scene scene = sceneWithBaseColour(alphaRampImage(64));
  scene.materials[0].baseColor.w = 0.5f;
  scene.materials[0].alphaMode = AlphaMode::Mask;
  scene.materials[0].doubleSided = true;
  PackedTextures packed = packSceneTextures(scene);
  uint32_t ref = packed.materials[0].baseColorTexture;
  auto expected = [](int x, int y) { return float((x + 3 * y) % 256) / 255.0f; };

  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {0.25f, 0.5f}), expected(16, 32));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {1.25f, 0.5f}), expected(16, 32));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {-0.75f, 2.5f}), expected(16, 32));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {0.0f, 0.0f}), expected(0, 0));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {1.0f, 1.0f}), expected(0, 0));  // fract(1) = 0
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {0.9999f, 0.0f}), expected(63, 0));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, ref, {NAN, 0.0f}), expected(0, 0));
  EXPECT_FLOAT_EQ(sampleAlphaNearest(packed, gpu::NO_TEXTURE, {0.3f, 0.3f}), 1.0f);

  const gpu::GpuMaterial& g = packed.materials[0];
  EXPECT_FLOAT_EQ(materialAlpha(packed, g, {0.25f, 0.5f}), 0.5f * expected(16, 32));
  EXPECT_EQ(g.flags, gpu::MATERIAL_ALPHA_MASK | gpu::MATERIAL_DOUBLE_SIDED);
  // The alpha channel is linear even in sRGB arrays, and colour decodes from sRGB.
  glm::vec4 t = sampleTexelNearest(packed, ref, {0.25f, 0.5f});
  EXPECT_FLOAT_EQ(t.w, expected(16, 32));
  EXPECT_NEAR(t.x, srgb8ToLinear(10), 1e-7f);
}

TEST(TexturePack, MaterialsCarryFactorsAndShareLayers) {
  Scene scene;
  scene.images = {solidImage(64, 64, {255, 255, 255, 255}), solidImage(256, 256, {0, 0, 0, 255})};
  Material a;
  a.baseColor = {0.1f, 0.2f, 0.3f, 1.0f};
  a.emissive = {4, 5, 6};
  a.metallic = 0.25f;
  a.roughness = 0.75f;
  a.alphaCutoff = 0.3f;
  a.normalScale = 0.6f;
  a.alphaMode = AlphaMode::Blend;
  a.baseColorTexture = 0;
  a.emissiveTexture = 1;
  Material b;
  b.baseColorTexture = 0;  // the same (image, encoding): the same layer
  b.emissiveTexture = 0;
  scene.materials = {a, b, Material{}};
  PackedTextures packed = packSceneTextures(scene);

  ASSERT_EQ(packed.materials.size(), 3u);
  const gpu::GpuMaterial& ga = packed.materials[0];
  EXPECT_EQ(ga.baseColor, a.baseColor);
  EXPECT_EQ(ga.emissive, a.emissive);
  EXPECT_EQ(ga.metallic, 0.25f);
  EXPECT_EQ(ga.roughness, 0.75f);
  EXPECT_EQ(ga.alphaCutoff, 0.3f);
  EXPECT_EQ(ga.normalScale, 0.6f);
  EXPECT_EQ(ga.flags, gpu::MATERIAL_ALPHA_BLEND);
  EXPECT_EQ(ga.baseColorTexture, makeTextureRef(0, 0, true));
  EXPECT_EQ(ga.emissiveTexture, makeTextureRef(0, 2, true));
  EXPECT_EQ(packed.materials[1].baseColorTexture, ga.baseColorTexture);
  EXPECT_EQ(packed.materials[1].emissiveTexture, ga.baseColorTexture);
  EXPECT_EQ(packed.materials[2].baseColorTexture, gpu::NO_TEXTURE);
  EXPECT_EQ(packed.materials[2].flags, 0u);
  EXPECT_EQ(packed.arrays.size(), 2u);
  EXPECT_EQ(packed.find(0, true)->layers, 1u);
  EXPECT_EQ(packed.find(0, false), nullptr);
  EXPECT_THROW(sampleAlphaNearest(packed, makeTextureRef(3, 0, true), {0, 0}), Error);
}

TEST(TexturePack, SrgbCodesRoundTrip) {
  for (int c = 0; c < 256; ++c) EXPECT_EQ(linearToSrgb8(srgb8ToLinear(uint8_t(c))), c);
  EXPECT_EQ(linearToSrgb8(0.5f), 188);
  EXPECT_EQ(linearToSrgb8(-1.0f), 0);
  EXPECT_EQ(linearToSrgb8(2.0f), 255);
  EXPECT_NEAR(srgb8ToLinear(188), 0.5f, 0.003f);
}

// The fast table-driven encoder must agree with the IEC 61966-2-1 formula rounded in sRGB space.
TEST(TexturePack, SrgbEncoderMatchesFormula) {
  for (int i = 0; i <= 200000; ++i) {
    float x = float(i) / 200000.0f;
    double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(double(x), 1.0 / 2.4) - 0.055;
    ASSERT_EQ(linearToSrgb8(x), std::lround(v * 255.0)) << "linear " << x;
  }
}

// A real alpha-masked material: the flowers' base colour alpha has both cut-out and solid
// texels, and the CPU alpha test sees them through the packed texture.
TEST(TexturePack, GlassVaseFlowersAlphaMask) {
  Scene scene =
      loadGltf(test::sharedDir() + "/scenes/glass_vase_flowers/glTF/GlassVaseFlowers.gltf");
  PackedTextures packed = packSceneTextures(scene);
  ASSERT_EQ(packed.materials.size(), scene.materials.size());
  size_t flowers = 0;
  while (scene.materials[flowers].name != "Flowers") ++flowers;
  const gpu::GpuMaterial& g = packed.materials[flowers];
  EXPECT_TRUE(g.flags & gpu::MATERIAL_ALPHA_MASK);
  ASSERT_NE(g.baseColorTexture, gpu::NO_TEXTURE);
  EXPECT_EQ(textureRefSizeClass(g.baseColorTexture), 4u);  // 1024 x 1024
  int cut = 0, total = 0;
  for (float v = 0.0f; v < 1.0f; v += 1.0f / 64)
    for (float u = 0.0f; u < 1.0f; u += 1.0f / 64, ++total)
      cut += materialAlpha(packed, g, {u, v}) < g.alphaCutoff;
  EXPECT_GT(cut, total / 20);
  EXPECT_LT(cut, total * 19 / 20);
}

}  // namespace
}  // namespace bounce
