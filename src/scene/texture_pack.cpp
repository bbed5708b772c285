#include "scene/texture_pack.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/parallel_for.h"

namespace bounce {
namespace {

constexpr uint32_t kMaxSide = gpu::TEXTURE_MIN_SIZE << (gpu::TEXTURE_SIZE_CLASSES - 1);  // 2048
constexpr uint32_t kMaxLayers = 0x10000;  // the layer field of a reference has 16 bits

double srgbDecode(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Linear value of each 8-bit sRGB code.
const std::array<float, 256>& srgbDecodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int c = 0; c < 256; ++c) t[size_t(c)] = float(srgbDecode(c / 255.0));
    return t;
  }();
  return table;
}

// thresholds[c] = the linear value halfway (in sRGB space) between codes c and c + 1, so the
// number of thresholds <= x is x's correctly rounded code: exact, and cheaper than pow().
const std::array<float, 255>& srgbEncodeThresholds() {
  static const std::array<float, 255> table = [] {
    std::array<float, 255> t{};
    for (int c = 0; c < 255; ++c) {
      // Rounded up to a float, so that for any float x: x >= t[c] exactly when x lies at or
      // above the true threshold.
      double threshold = srgbDecode((c + 0.5) / 255.0);
      float f = float(threshold);
      t[size_t(c)] = double(f) < threshold ? std::nextafter(f, 2.0f) : f;
    }
    return t;
  }();
  return table;
}

// Encoding is the hot loop of packing (every texel of every mip), so instead of a binary search
// over the thresholds, a table over [0, 1) gives the code of each bin's lower edge and a short
// scan finishes: bins are narrower than the sRGB code steps, so it takes at most a few steps.
constexpr size_t kEncodeBins = 4096;

const std::array<uint8_t, kEncodeBins>& srgbEncodeBinStart() {
  static const std::array<uint8_t, kEncodeBins> table = [] {
    const std::array<float, 255>& t = srgbEncodeThresholds();
    std::array<uint8_t, kEncodeBins> start{};
    for (size_t bin = 0; bin < kEncodeBins; ++bin) {
      float lowerEdge = float(bin) / kEncodeBins;
      start[bin] = uint8_t(std::upper_bound(t.begin(), t.end(), lowerEdge) - t.begin());
    }
    return start;
  }();
  return table;
}

uint8_t linearToUnorm8(float v) {
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

uint32_t sideForImage(const Image& image) {
  uint32_t largest = uint32_t(std::max(image.width, image.height));
  return std::clamp(std::bit_ceil(largest), gpu::TEXTURE_MIN_SIZE, kMaxSide);
}

uint32_t sizeClassOfSide(uint32_t side) {
  return uint32_t(std::countr_zero(side / gpu::TEXTURE_MIN_SIZE));
}

// One image in one encoding, with its place in the packed arrays.
struct PackJob {
  int image = -1;
  bool srgb = false;
  uint32_t sizeClass = 0;
  uint32_t layer = 0;
};

// Source texels as linear floats; alpha is linear in every encoding.
glm::vec4 decodeTexel(const uint8_t* rgba, bool srgb) {
  if (!srgb) return glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3]) / 255.0f;
  const std::array<float, 256>& table = srgbDecodeTable();
  return {table[rgba[0]], table[rgba[1]], table[rgba[2]], rgba[3] / 255.0f};
}

// For each destination texel along one axis: the two source texels bilinear filtering blends
// and the weight of the second. Texel centres are matched ((x + 0.5) * scale - 0.5) and
// neighbours wrap, as the GPU's repeat sampler would.
struct AxisTap {
  uint32_t i0, i1;
  float w1;
};

std::vector<AxisTap> axisTaps(uint32_t sourceSize, uint32_t destSize) {
  std::vector<AxisTap> taps(destSize);
  double scale = double(sourceSize) / destSize;
  for (uint32_t x = 0; x < destSize; ++x) {
    double s = (x + 0.5) * scale - 0.5;
    double base = std::floor(s);
    int64_t i0 = (int64_t(base) % sourceSize + sourceSize) % sourceSize;
    taps[x] = {uint32_t(i0), uint32_t((i0 + 1) % sourceSize), float(s - base)};
  }
  return taps;
}

// The image as side x side linear texels. Images already of that size are only decoded
// (bilinear at matched texel centres is the identity there anyway).
std::vector<glm::vec4> resampleToSquare(const Image& image, bool srgb, uint32_t side) {
  std::vector<glm::vec4> out(size_t(side) * side);
  auto source = [&](uint32_t x, uint32_t y) {
    return decodeTexel(&image.rgba[(size_t(y) * uint32_t(image.width) + x) * 4], srgb);
  };
  if (uint32_t(image.width) == side && uint32_t(image.height) == side) {
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x) out[size_t(y) * side + x] = source(x, y);
    return out;
  }
  std::vector<AxisTap> columns = axisTaps(uint32_t(image.width), side);
  std::vector<AxisTap> rows = axisTaps(uint32_t(image.height), side);
  for (uint32_t y = 0; y < side; ++y) {
    const AxisTap& r = rows[y];
    for (uint32_t x = 0; x < side; ++x) {
      const AxisTap& c = columns[x];
      glm::vec4 top = glm::mix(source(c.i0, r.i0), source(c.i1, r.i0), c.w1);
      glm::vec4 bottom = glm::mix(source(c.i0, r.i1), source(c.i1, r.i1), c.w1);
      out[size_t(y) * side + x] = glm::mix(top, bottom, r.w1);
    }
  }
  return out;
}

// The mean of four texels. With coverage weighting (colour textures, whose alpha is opacity),
// the colour is the mean of the texels weighted by their alpha: the colour of cut-out texels
// (alpha 0) is never seen at mip 0 and often arbitrary (white, black, bled), so a plain mean
// would tint every coarse mip of a leaf or fence texture with it; the GI's 16-texel mip reads
// (RestirGiSettings::materialTextureSide) saw the sorrel leaves' materials 6.8 % brighter than
// full resolution that way, 2.3 % with this (test_restir_gi, CoarseMipMaterialsKeepTheGi). Alpha
// itself is the plain mean (the fraction covered).
glm::vec4 blockMean(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, const glm::vec4& d,
                    bool coverageWeighted) {
  glm::vec4 mean = 0.25f * (a + b + c + d);
  float coverage = a.w + b.w + c.w + d.w;
  if (!coverageWeighted || !(coverage > 0.0f)) return mean;
  glm::vec3 colour =
      (glm::vec3(a) * a.w + glm::vec3(b) * b.w + glm::vec3(c) * c.w + glm::vec3(d) * d.w) /
      coverage;
  return glm::vec4(colour, mean.w);
}

// The next mip: each texel is the mean of a 2x2 block (a box filter; sides are powers of two,
// so blocks never straddle).
std::vector<glm::vec4> halve(const std::vector<glm::vec4>& level, uint32_t side,
                             bool coverageWeighted) {
  uint32_t half = side / 2;
  std::vector<glm::vec4> out(size_t(half) * half);
  for (uint32_t y = 0; y < half; ++y)
    for (uint32_t x = 0; x < half; ++x) {
      const glm::vec4* row0 = &level[size_t(2 * y) * side + 2 * x];
      const glm::vec4* row1 = row0 + side;
      out[size_t(y) * half + x] = blockMean(row0[0], row0[1], row1[0], row1[1], coverageWeighted);
    }
  return out;
}

void encodeLevel(const std::vector<glm::vec4>& level, bool srgb, uint8_t* dest) {
  for (size_t i = 0; i < level.size(); ++i) {
    const glm::vec4& v = level[i];
    for (int c = 0; c < 3; ++c) dest[4 * i + c] = srgb ? linearToSrgb8(v[c]) : linearToUnorm8(v[c]);
    dest[4 * i + 3] = linearToUnorm8(v.w);
  }
}

// Fills the job's layer at every mip of its array.
void packLayer(const Scene& scene, const PackJob& job, PackedTextureArray& array) {
  std::vector<glm::vec4> level =
      resampleToSquare(scene.images[size_t(job.image)], job.srgb, array.side);
  for (uint32_t mip = 0; mip < array.mipCount; ++mip) {
    encodeLevel(level, job.srgb, &array.texels[array.texelOffset(job.layer, mip, 0, 0)]);
    // sRGB textures are the colour ones (base colour, emissive), whose alpha is opacity; the
    // linear ones (normals, metallic-roughness, occlusion) have no meaningful alpha.
    if (mip + 1 < array.mipCount) level = halve(level, array.mipSide(mip), job.srgb);
  }
}

// The (image, encoding) pairs the materials use, in order of first use, each with a layer in
// its (class, encoding) array.
class JobList {
 public:
  explicit JobList(const Scene& scene) : scene_(scene) {}

  // The texture reference for `image` in `srgb` encoding; NO_TEXTURE for -1.
  uint32_t refFor(int image, bool srgb) {
    if (image < 0) return gpu::NO_TEXTURE;
    checkImage(image);
    auto [it, inserted] = jobIndex_.emplace(std::pair{image, srgb}, jobs_.size());
    if (inserted) {
      PackJob job{image, srgb, sizeClassOfSide(sideForImage(scene_.images[size_t(image)]))};
      job.layer = layerCount_[{job.sizeClass, srgb}]++;
      if (job.layer >= kMaxLayers)
        fail("texture packing: more than {} textures of side {} ({})", kMaxLayers,
             gpu::TEXTURE_MIN_SIZE << job.sizeClass, srgb ? "sRGB" : "linear");
      jobs_.push_back(job);
    }
    const PackJob& job = jobs_[it->second];
    return makeTextureRef(job.layer, job.sizeClass, job.srgb);
  }

  const std::vector<PackJob>& jobs() const { return jobs_; }
  const std::map<std::pair<uint32_t, bool>, uint32_t>& layerCounts() const { return layerCount_; }

 private:
  // The packer reads pixels directly, so it re-checks what validateScene promises.
  void checkImage(int image) const {
    if (size_t(image) >= scene_.images.size())
      fail("texture packing: image {} does not exist ({} images)", image, scene_.images.size());
    const Image& img = scene_.images[size_t(image)];
    if (img.width <= 0 || img.height <= 0 ||
        img.rgba.size() != size_t(img.width) * size_t(img.height) * 4)
      fail("texture packing: image {} ('{}') has inconsistent size {}x{}", image, img.name,
           img.width, img.height);
  }

  const Scene& scene_;
  std::vector<PackJob> jobs_;
  std::map<std::pair<int, bool>, size_t> jobIndex_;
  std::map<std::pair<uint32_t, bool>, uint32_t> layerCount_;  // (class, sRGB) -> layers
};

gpu::GpuMaterial gpuMaterial(const Material& m, JobList& jobs) {
  gpu::GpuMaterial g{};
  g.baseColor = m.baseColor;
  g.emissive = m.emissive;
  g.metallic = m.metallic;
  g.roughness = m.roughness;
  g.alphaCutoff = m.alphaCutoff;
  g.normalScale = m.normalScale;
  g.flags = (m.doubleSided ? gpu::MATERIAL_DOUBLE_SIDED : 0u) |
            (m.alphaMode == AlphaMode::Mask ? gpu::MATERIAL_ALPHA_MASK : 0u) |
            (m.alphaMode == AlphaMode::Blend ? gpu::MATERIAL_ALPHA_BLEND : 0u);
  // Colours are sRGB-encoded in glTF images; data maps (normals, metallic-roughness) are not.
  g.baseColorTexture = jobs.refFor(m.baseColorTexture, true);
  g.metallicRoughnessTexture = jobs.refFor(m.metallicRoughnessTexture, false);
  g.normalTexture = jobs.refFor(m.normalTexture, false);
  g.emissiveTexture = jobs.refFor(m.emissiveTexture, true);
  return g;
}

PackedTextureArray emptyArray(uint32_t sizeClass, bool srgb, uint32_t layers) {
  PackedTextureArray a;
  a.sizeClass = sizeClass;
  a.srgb = srgb;
  a.side = gpu::TEXTURE_MIN_SIZE << sizeClass;
  a.mipCount = uint32_t(std::countr_zero(a.side)) + 1;
  a.layers = layers;
  a.texels.resize(a.mipOffset(a.mipCount));
  return a;
}

const uint8_t* texelAt(const PackedTextures& textures, uint32_t ref, glm::vec2 uv) {
  const PackedTextureArray* array = textures.find(textureRefSizeClass(ref), textureRefIsSrgb(ref));
  if (!array || textureRefLayer(ref) >= array->layers)
    fail("texture reference {:#x} refers to a texture that was not packed", ref);
  auto texelCoordinate = [&](float u) {
    if (!std::isfinite(u)) return 0u;
    float t = std::floor((u - std::floor(u)) * float(array->side));  // floor(fract(u) * side)
    return uint32_t(std::clamp(t, 0.0f, float(array->side - 1)));
  };
  return &array->texels[array->texelOffset(textureRefLayer(ref), 0, texelCoordinate(uv.x),
                                           texelCoordinate(uv.y))];
}

}  // namespace

size_t PackedTextureArray::mipOffset(uint32_t mip) const {
  size_t offset = 0;
  for (uint32_t m = 0; m < mip; ++m) offset += layerBytes(m) * layers;
  return offset;
}

size_t PackedTextureArray::texelOffset(uint32_t layer, uint32_t mip, uint32_t x, uint32_t y) const {
  return mipOffset(mip) + layer * layerBytes(mip) + (size_t(y) * mipSide(mip) + x) * 4;
}

const PackedTextureArray* PackedTextures::find(uint32_t sizeClass, bool srgb) const {
  for (const PackedTextureArray& a : arrays)
    if (a.sizeClass == sizeClass && a.srgb == srgb) return &a;
  return nullptr;
}

uint32_t makeTextureRef(uint32_t layer, uint32_t sizeClass, bool srgb) {
  return layer | (sizeClass << 16) | (srgb ? gpu::TEXTURE_SRGB_BIT : 0u);
}

PackedTextures packSceneTextures(const Scene& scene) {
  PackedTextures packed;
  JobList jobs(scene);
  for (const Material& m : scene.materials) packed.materials.push_back(gpuMaterial(m, jobs));

  std::map<std::pair<uint32_t, bool>, size_t> arrayIndex;
  for (const auto& [key, layers] : jobs.layerCounts()) {
    arrayIndex[key] = packed.arrays.size();
    packed.arrays.push_back(emptyArray(key.first, key.second, layers));
  }
  // Jobs write disjoint layers, so they can fill the shared arrays concurrently.
  parallelFor(jobs.jobs().size(), [&](size_t i) {
    const PackJob& job = jobs.jobs()[i];
    packLayer(scene, job, packed.arrays[arrayIndex.at({job.sizeClass, job.srgb})]);
  });
  return packed;
}

glm::vec4 sampleTexelNearest(const PackedTextures& textures, uint32_t textureRef, glm::vec2 uv) {
  if (textureRef == gpu::NO_TEXTURE) return glm::vec4(1.0f);
  return decodeTexel(texelAt(textures, textureRef, uv), textureRefIsSrgb(textureRef));
}

float sampleAlphaNearest(const PackedTextures& textures, uint32_t textureRef, glm::vec2 uv) {
  if (textureRef == gpu::NO_TEXTURE) return 1.0f;
  return texelAt(textures, textureRef, uv)[3] / 255.0f;
}

float materialAlpha(const PackedTextures& textures, const gpu::GpuMaterial& material,
                    glm::vec2 uv) {
  return material.baseColor.w * sampleAlphaNearest(textures, material.baseColorTexture, uv);
}

float srgb8ToLinear(uint8_t code) {
  return srgbDecodeTable()[code];
}

uint8_t linearToSrgb8(float linear) {
  const std::array<float, 255>& t = srgbEncodeThresholds();
  const std::array<uint8_t, kEncodeBins>& start = srgbEncodeBinStart();
  if (!(linear > 0.0f)) return 0;  // also maps NaN to 0
  if (linear >= 1.0f) return 255;
  uint32_t code = start[size_t(linear * kEncodeBins)];
  while (code < 255 && linear >= t[code]) ++code;
  return uint8_t(code);
}

}  // namespace bounce
