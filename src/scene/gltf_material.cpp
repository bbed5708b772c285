// glTF materials (metallic-roughness, emissive strength, alpha, texture transforms) and the
// images they use, decoded to RGBA8 with stb_image.
#include <climits>
#include <cmath>

#include <stb_image.h>  // declarations only; Debian's libstb provides the implementation

#include "core/error.h"
#include "core/parallel_for.h"
#include "scene/gltf_internal.h"

namespace bounce::gltf {
namespace {

// Images larger than this are rejected before decoding: the texture packer caps sides at
// 2048 anyway, and a forged header must not make us allocate gigabytes (2^26 pixels = 256 MiB
// of RGBA8, e.g. 8192 x 8192 or a 16384 x 4096 panorama).
constexpr int kMaxImageSide = 16384;
constexpr int64_t kMaxImagePixels = int64_t(1) << 26;

const tinygltf::Value* extensionObject(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return object.Get(key).GetNumberAsDouble();
}

glm::vec2 vec2Or(const tinygltf::Value& object, const char* key, glm::vec2 fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& array = object.Get(key);
  if (array.ArrayLen() != 2 || !array.Get(0).IsNumber() || !array.Get(1).IsNumber())
    return fallback;
  return {float(array.Get(0).GetNumberAsDouble()), float(array.Get(1).GetNumberAsDouble())};
}

// KHR_texture_transform as one matrix: uv' = T(offset) * R(rotation) * S(scale) * uv. The
// rotation turns UVs counter-clockwise in the image (v points down), which the ratified
// extension's example (offset [0,1], rotation 90 degrees, scale 0.5 -> lower-left quadrant)
// pins down.
glm::mat3 textureTransformMatrix(const tinygltf::Value& transform) {
  glm::vec2 offset = vec2Or(transform, "offset", glm::vec2(0.0f));
  glm::vec2 scale = vec2Or(transform, "scale", glm::vec2(1.0f));
  float angle = float(numberOr(transform, "rotation", 0.0));
  float c = std::cos(angle), s = std::sin(angle);
  glm::mat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);  // column-major
  glm::mat3 rotation(c, -s, 0, s, c, 0, 0, 0, 1);
  glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return translation * rotation * scaling;
}

bool nearlyEqual(const glm::mat3& a, const glm::mat3& b) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (std::abs(a[c][r] - b[c][r]) > 1e-6f) return false;
  return true;
}

bool isFiniteMatrix(const glm::mat3& m) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

Material defaultMaterial() {
  Material m;
  m.name = "default";
  m.baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

std::string imageLabel(const tinygltf::Image& image, int index) {
  if (!image.uri.empty()) return fmt::format("image {} '{}'", index, image.uri);
  if (image.bufferView >= 0)
    return fmt::format("image {} '{}' (bufferView {})", index, image.name, image.bufferView);
  return fmt::format("image {} '{}' (data URI)", index, image.name);
}

// The encoded bytes of an image: a range-checked buffer view, or what our tinygltf image
// callback kept (external file or data URI). tinygltf only warns when an external image file
// is missing, leaving no bytes; that is an error here because the material needs it.
std::span<const uint8_t> encodedImageBytes(const Source& src, int index, const std::string& label) {
  const tinygltf::Image& image = src.model.images[size_t(index)];
  if (image.bufferView >= 0) return bufferViewBytes(src, image.bufferView, label);
  if (image.as_is && !image.image.empty()) return image.image;
  fail("{}: {}: the image file is missing, empty or unreadable", src.path, label);
}

const char* decodeFailure() {
  const char* reason = stbi_failure_reason();  // thread-local in stb_image 2.27
  return reason ? reason : "unknown reason";
}

Image decodeImage(const Source& src, int index) {
  const tinygltf::Image& source = src.model.images[size_t(index)];
  std::string label = imageLabel(source, index);
  std::span<const uint8_t> bytes = encodedImageBytes(src, index, label);
  if (bytes.size() > size_t(INT_MAX))
    fail("{}: {}: {} encoded bytes exceed 2 GiB", src.path, label, bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels))
    fail("{}: {}: cannot decode the image ({})", src.path, label, decodeFailure());
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide ||
      int64_t(width) * height > kMaxImagePixels)
    fail("{}: {}: size {}x{} is outside 1..{} per side or above 2^26 pixels", src.path, label,
         width, height, kMaxImageSide);
  // Forcing 4 components gives every image the same RGBA8 layout (16-bit PNGs are reduced
  // to 8 bits by stb).
  uint8_t* pixels =
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 4);
  if (!pixels) fail("{}: {}: cannot decode the image ({})", src.path, label, decodeFailure());
  Image image;
  image.name = source.uri.empty() ? source.name : source.uri;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
  stbi_image_free(pixels);
  return image;
}

// What Bounce draws in place of each extension it ignores, by extension-name prefix.
struct IgnoredExtension {
  const char* name;
  const char* consequence;
};
constexpr IgnoredExtension kIgnoredExtensions[] = {
    {"KHR_materials_transmission", "surfaces are opaque (no transmission)"},
    {"KHR_materials_diffuse_transmission", "surfaces are opaque (no transmission)"},
    {"KHR_materials_volume", "surfaces are opaque (no volume)"},
    {"KHR_materials_unlit", "the material is lit like any other"},
    {"KHR_materials_pbrSpecularGlossiness", "the metallic-roughness fallback is used"},
    {"KHR_materials_variants", "each primitive keeps its default material"},
    {"KHR_materials_", "shaded as plain metallic-roughness"},
    {"KHR_draco_mesh_compression", "the uncompressed fallback data is used"},
    {"EXT_meshopt_compression", "the uncompressed fallback data is used"},
    {"KHR_texture_basisu", "textures without a PNG or JPEG source are dropped"},
    {"EXT_texture_", "textures without a PNG or JPEG source are dropped"},
    {"MSFT_texture_dds", "textures without a PNG or JPEG source are dropped"},
    {"EXT_mesh_gpu_instancing", "each node is drawn once, at its own transform"},
};

// Material extensions Bounce reads; every other one on a used material is named.
bool isReadMaterialExtension(const std::string& name) {
  return name == "KHR_materials_emissive_strength";
}

}  // namespace

bool isSupportedExtension(const std::string& name) {
  return name == "KHR_materials_emissive_strength" || name == "KHR_lights_punctual" ||
         name == "KHR_texture_transform" || name == "KHR_mesh_quantization" ||
         name == "KHR_xmp_json_ld" || name == "KHR_xmp";
}

std::string ignoredExtensionWarning(const std::string& name) {
  for (const IgnoredExtension& e : kIgnoredExtensions)
    if (name.starts_with(e.name)) return fmt::format("{} is ignored: {}", name, e.consequence);
  return fmt::format("{} is ignored", name);
}

uint32_t MaterialTable::sceneIndex(int gltfMaterial) {
  if (gltfMaterial < 0) {
    if (!defaultMaterial_) {
      defaultMaterial_ = uint32_t(scene_.materials.size());
      scene_.materials.push_back(defaultMaterial());
    }
    return *defaultMaterial_;
  }
  return convert(gltfMaterial).sceneIndex;
}

std::optional<glm::mat3> MaterialTable::uvTransform(int gltfMaterial) {
  if (gltfMaterial < 0) return std::nullopt;
  return convert(gltfMaterial).uvTransform;
}

void MaterialTable::ensureNotEmpty() {
  if (scene_.materials.empty()) sceneIndex(-1);
}

void MaterialTable::decodeImages() {
  parallelFor(gltfImageOfSceneImage_.size(),
              [&](size_t i) { scene_.images[i] = decodeImage(src_, gltfImageOfSceneImage_[i]); });
}

const MaterialTable::Converted& MaterialTable::convert(int gltfMaterial) {
  auto it = converted_.find(gltfMaterial);
  if (it != converted_.end()) return it->second;
  if (size_t(gltfMaterial) >= src_.model.materials.size())
    fail("{}: material {} does not exist ({} materials)", src_.path, gltfMaterial,
         src_.model.materials.size());
  std::optional<glm::mat3> transform;
  Material material = makeMaterial(gltfMaterial, transform);
  if (transform && nearlyEqual(*transform, glm::mat3(1.0f))) transform.reset();  // nothing to bake
  Converted entry{uint32_t(scene_.materials.size()), transform};
  scene_.materials.push_back(std::move(material));
  return converted_.emplace(gltfMaterial, entry).first->second;
}

// A factor from the file as float; JSON cannot hold NaN but 1e400 parses as infinity.
static float finiteFactor(const Source& src, double value, const std::string& where,
                          const char* name) {
  float f = float(value);
  if (!std::isfinite(f)) fail("{}: {}: {} is not finite", src.path, where, name);
  return f;
}

static AlphaMode parseAlphaMode(const Source& src, const std::string& mode,
                                const std::string& where) {
  if (mode == "MASK") return AlphaMode::Mask;
  if (mode == "BLEND") {
    warnIgnored(src, "alphaMode BLEND is drawn as an alpha mask at 0.5 (no blending)", "materials",
                where);
    return AlphaMode::Blend;
  }
  if (mode != "OPAQUE")
    warn(src, {.group = "unknown alphaMode, OPAQUE used",
               .things = "materials",
               .where = where,
               .detail = fmt::format("unknown alphaMode '{}', using OPAQUE", mode)});
  return AlphaMode::Opaque;
}

// Features of a used material that Bounce does not draw, each named once per file.
static void warnIgnoredMaterialFeatures(const Source& src, const tinygltf::Material& m,
                                        const std::string& where) {
  if (m.occlusionTexture.index >= 0)
    warnIgnored(src, "occlusionTexture is ignored: the renderer computes its own occlusion",
                "materials", where);
  for (const auto& [name, value] : m.extensions)
    if (!isReadMaterialExtension(name))
      warnIgnored(src, ignoredExtensionWarning(name), "materials", where);
}

Material MaterialTable::makeMaterial(int index, std::optional<glm::mat3>& uvTransform) {
  const tinygltf::Material& m = src_.model.materials[size_t(index)];
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  std::string where = describe("material", index, m.name);
  Material mat;
  mat.name = m.name.empty() ? fmt::format("material {}", index) : m.name;
  for (int c = 0; c < 4; ++c)
    mat.baseColor[c] = finiteFactor(src_, pbr.baseColorFactor[size_t(c)], where, "baseColorFactor");
  mat.metallic =
      glm::clamp(finiteFactor(src_, pbr.metallicFactor, where, "metallicFactor"), 0.f, 1.f);
  mat.roughness =
      glm::clamp(finiteFactor(src_, pbr.roughnessFactor, where, "roughnessFactor"), 0.f, 1.f);
  const tinygltf::Value* strengthExt =
      extensionObject(m.extensions, "KHR_materials_emissive_strength");
  float strength = strengthExt ? finiteFactor(src_, numberOr(*strengthExt, "emissiveStrength", 1.0),
                                              where, "emissiveStrength")
                               : 1.0f;
  for (int c = 0; c < 3; ++c)
    mat.emissive[c] =
        std::max(finiteFactor(src_, m.emissiveFactor[size_t(c)], where, "emissiveFactor"), 0.f) *
        std::max(strength, 0.0f);
  warnIgnoredMaterialFeatures(src_, m, where);
  mat.normalScale = finiteFactor(src_, m.normalTexture.scale, where, "normalTexture.scale");
  mat.alphaMode = parseAlphaMode(src_, m.alphaMode, where);
  mat.alphaCutoff = glm::max(finiteFactor(src_, m.alphaCutoff, where, "alphaCutoff"), 0.0f);
  mat.doubleSided = m.doubleSided;
  mat.baseColorTexture =
      imageFor(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
               pbr.baseColorTexture.extensions, "baseColorTexture", index, uvTransform);
  mat.metallicRoughnessTexture = imageFor(
      pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
      pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture", index, uvTransform);
  mat.normalTexture = imageFor(m.normalTexture.index, m.normalTexture.texCoord,
                               m.normalTexture.extensions, "normalTexture", index, uvTransform);
  mat.emissiveTexture =
      imageFor(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions,
               "emissiveTexture", index, uvTransform);
  return mat;
}

// Resolves a material's texture slot to a scene image (queued for decoding), checking every
// index. The scene model has one UV set and one UV transform per material, so the first
// textured slot's KHR_texture_transform is baked into the geometry's UVs (base colour comes
// first: it is what the eye checks); a different transform on a later slot is approximated
// by that one, with a warning.
int MaterialTable::imageFor(int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
                            const std::string& slot, int material,
                            std::optional<glm::mat3>& uvTransform) {
  if (texture < 0) return -1;
  const tinygltf::Model& model = src_.model;
  std::string where = fmt::format(
      "{} {}", describe("material", material, model.materials[size_t(material)].name), slot);
  if (size_t(texture) >= model.textures.size())
    fail("{}: {} refers to texture {} ({} textures)", src_.path, where, texture,
         model.textures.size());
  int source = model.textures[size_t(texture)].source;
  if (source < 0) {
    warn(src_, {.group = "textures without a PNG or JPEG image are ignored",
                .things = "texture slots",
                .where = where,
                .detail = fmt::format("texture {} has no image we can read; ignored", texture)});
    return -1;
  }
  warnIgnoredSampler(texture, where);
  if (size_t(source) >= model.images.size())
    fail("{}: texture {} refers to image {} ({} images)", src_.path, texture, source,
         model.images.size());

  glm::mat3 transform(1.0f);
  if (const tinygltf::Value* t = extensionObject(extensions, "KHR_texture_transform")) {
    transform = textureTransformMatrix(*t);
    texCoord = int(glm::clamp(numberOr(*t, "texCoord", texCoord), 0.0, 255.0));
    if (!isFiniteMatrix(transform))
      fail("{}: {}: KHR_texture_transform is not finite", src_.path, where);
  }
  if (!uvTransform)
    uvTransform = transform;
  else if (!nearlyEqual(*uvTransform, transform))
    warn(src_, {.group = "a KHR_texture_transform that differs from the material's first "
                         "texture's is replaced by that one",
                .things = "texture slots",
                .where = where});
  if (texCoord != 0)
    warnIgnored(src_, "TEXCOORD_1 and higher are ignored: TEXCOORD_0 is used instead",
                "texture slots", fmt::format("{} (TEXCOORD_{})", where, texCoord));

  auto [it, inserted] = sceneImageOfGltfImage_.emplace(source, int(scene_.images.size()));
  if (inserted) {
    scene_.images.emplace_back();  // filled by decodeImages()
    gltfImageOfSceneImage_.push_back(source);
  }
  return it->second;
}

// The texture arrays are sampled with one sampler: linear filtering with linear mipmaps,
// repeat wrapping (rt/gpu_scene.cpp). A glTF sampler asking for anything else is named.
void MaterialTable::warnIgnoredSampler(int texture, const std::string& where) {
  if (!samplerChecked_.insert(texture).second) return;
  int sampler = src_.model.textures[size_t(texture)].sampler;
  if (sampler < 0 || size_t(sampler) >= src_.model.samplers.size()) return;
  const tinygltf::Sampler& s = src_.model.samplers[size_t(sampler)];
  const char* differs = nullptr;
  if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
    differs = "wrap mode";
  else if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
           s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
           s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
           s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR)
    differs = "nearest filtering";
  if (!differs) return;
  warnIgnored(src_,
              "sampler wrap and filter modes are ignored: textures repeat and filter linearly "
              "with mipmaps",
              "textures", fmt::format("{} (sampler {}: {})", where, sampler, differs));
}

}  // namespace bounce::gltf
