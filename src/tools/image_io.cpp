#include "tools/image_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include "core/error.h"

namespace bounce {

ImageRGBA32F::ImageRGBA32F(int w, int h, glm::vec4 fill) : width(w), height(h) {
  pixels.resize(pixelCount() * 4);
  for (size_t i = 0; i < pixelCount(); ++i) {
    for (int c = 0; c < 4; ++c) pixels[4 * i + c] = fill[c];
  }
}

glm::vec4 ImageRGBA32F::at(int x, int y) const {
  const float* p = pixel(x, y);
  return {p[0], p[1], p[2], p[3]};
}

void ImageRGBA32F::set(int x, int y, const glm::vec4& rgba) {
  float* p = pixel(x, y);
  for (int c = 0; c < 4; ++c) p[c] = rgba[c];
}

float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  if (linear <= 0.0031308f) return linear * 12.92f;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::string imageExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool isHdrExtension(const std::string& path) {
  return imageExtension(path) == "exr";
}

bool isLdrExtension(const std::string& path) {
  const std::string ext = imageExtension(path);
  return ext == "png" || ext == "jpg" || ext == "jpeg";
}

namespace {

void requireReadableFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: no such file", path);
  if (!std::filesystem::is_regular_file(path, ec)) fail("{}: not a regular file", path);
}

void requireSaneSize(const std::string& path, long long width, long long height) {
  if (width <= 0 || height <= 0) fail("{}: invalid image size {}x{}", path, width, height);
  if (width > kMaxImageSide || height > kMaxImageSide ||
      size_t(width) * size_t(height) > kMaxImagePixels) {
    fail("{}: image size {}x{} exceeds the limit ({} per side, {} pixels in total)", path, width,
         height, kMaxImageSide, kMaxImagePixels);
  }
}

// tinyexr hands back a malloc'ed message that must be released with its own function.
std::string takeExrMessage(const char* message) {
  std::string text = message ? message : "unknown error";
  if (message) FreeEXRErrorMessage(message);
  return text;
}

// The bytes of a file, at most `limit` of them.
std::string readPrefix(const std::string& path, size_t limit) {
  std::string bytes(limit, '\0');
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) fail("{}: cannot open", path);
  bytes.resize(std::fread(bytes.data(), 1, limit, file));
  std::fclose(file);
  return bytes;
}

// Walks a single-part scanline/tiled EXR header's attributes (name, type, size, value; an empty
// name ends it) before tinyexr parses it: Debian's tinyexr asserts, that is aborts the process,
// on some malformed attributes (a `tiledesc` of the wrong size, found by fuzz/fuzz_image), so
// every attribute must lie inside the file and the fixed-size types must have their size.
void checkExrAttributes(const std::string& path) {
  constexpr size_t kMaxHeaderBytes = size_t(1) << 20;
  const std::string bytes = readPrefix(path, kMaxHeaderBytes);
  size_t at = 8;  // magic number and version
  auto readName = [&](const char* what) {
    const size_t end = bytes.find('\0', at);
    if (end == std::string::npos || end - at > 255)
      fail("{}: invalid EXR header: unterminated or too long attribute {} at byte {}", path, what,
           at);
    std::string name = bytes.substr(at, end - at);
    at = end + 1;
    return name;
  };
  struct FixedSize {
    const char* type;  // or, in kStandard, the attribute's name
    uint32_t bytes;
  };
  static const FixedSize kFixed[] = {
      {"box2i", 16},   {"box2f", 16},   {"compression", 1},     {"lineOrder", 1}, {"tiledesc", 9},
      {"int", 4},      {"float", 4},    {"double", 8},          {"v2i", 8},       {"v2f", 8},
      {"v3i", 12},     {"v3f", 12},     {"m33f", 36},           {"m44f", 64},     {"envmap", 1},
      {"rational", 8}, {"timecode", 8}, {"chromaticities", 32}, {"keycode", 28}};
  static const FixedSize kStandard[] = {{"tiles", 9},
                                        {"dataWindow", 16},
                                        {"displayWindow", 16},
                                        {"compression", 1},
                                        {"lineOrder", 1},
                                        {"pixelAspectRatio", 4},
                                        {"screenWindowWidth", 4},
                                        {"screenWindowCenter", 8},
                                        {"chunkCount", 4}};
  for (;;) {
    const std::string name = readName("name");
    if (name.empty()) return;
    const std::string type = readName("type");
    if (at + 4 > bytes.size()) fail("{}: invalid EXR header: attribute '{}' cut off", path, name);
    uint32_t size = 0;
    for (int k = 3; k >= 0; --k) size = (size << 8) | uint8_t(bytes[at + size_t(k)]);
    at += 4;
    if (size > bytes.size() - at)
      fail("{}: invalid EXR header: attribute '{}' of {} bytes runs past the header", path, name,
           size);
    for (const FixedSize& f : kFixed)
      if (type == f.type && size != f.bytes)
        fail("{}: invalid EXR header: attribute '{}' of type {} has {} bytes, expected {}", path,
             name, type, size, f.bytes);
    // tinyexr reads the standard attributes by name, whatever type the file gives them.
    for (const FixedSize& f : kStandard)
      if (name == f.type && size != f.bytes)
        fail("{}: invalid EXR header: attribute '{}' has {} bytes, expected {}", path, name, size,
             f.bytes);
    at += size;
  }
}

void checkExrHeader(const std::string& path) {
  EXRVersion version;
  if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS) {
    fail("{}: not an OpenEXR file (bad magic number or version)", path);
  }
  if (version.multipart || version.non_image) {
    fail("{}: multi-part and deep EXR files are not supported", path);
  }
  checkExrAttributes(path);
  EXRHeader header;
  InitEXRHeader(&header);
  const char* message = nullptr;
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &message) != TINYEXR_SUCCESS) {
    FreeEXRHeader(&header);  // a failed parse may leave fields allocated (fuzz/fuzz_image)
    fail("{}: invalid EXR header: {}", path, takeExrMessage(message));
  }
  const long long width = (long long)header.data_window.max_x - header.data_window.min_x + 1;
  const long long height = (long long)header.data_window.max_y - header.data_window.min_y + 1;
  FreeEXRHeader(&header);
  requireSaneSize(path, width, height);
}

ImageRGBA32F readExr(const std::string& path) {
  checkExrHeader(path);
  float* rgba = nullptr;
  int width = 0, height = 0;
  const char* message = nullptr;
  if (LoadEXR(&rgba, &width, &height, path.c_str(), &message) != TINYEXR_SUCCESS) {
    fail("{}: cannot read EXR (truncated or corrupt?): {}", path, takeExrMessage(message));
  }
  ImageRGBA32F image;
  image.width = width;
  image.height = height;
  image.pixels.assign(rgba, rgba + image.pixelCount() * 4);
  std::free(rgba);
  return image;
}

// 8-bit codes to linear, once: decoding a 1080p PNG then costs no pow() calls.
const std::array<float, 256>& srgb8ToLinearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

std::string stbReason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "unknown error";
}

template <typename Sample>
void decodeSrgb(const Sample* samples, ImageRGBA32F& image) {
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    for (int c = 0; c < 4; ++c) {
      const Sample s = samples[4 * i + c];
      float value;
      if constexpr (sizeof(Sample) == 1) {
        value = c < 3 ? srgb8ToLinearTable()[s] : float(s) / 255.0f;
      } else {
        value = c < 3 ? srgbToLinear(float(s) / 65535.0f) : float(s) / 65535.0f;
      }
      image.pixels[4 * i + c] = value;
    }
  }
}

// stb also decodes BMP, TGA, PSD, GIF, HDR, PIC and PNM, some of them (TGA) without a magic
// number, so arbitrary bytes named .png could decode as one of those (found by fuzz/fuzz_image:
// a 106-byte file that took 10 s). Only files that start with the PNG or JPEG signature reach
// stb.
bool hasPngOrJpegSignature(const std::string& path) {
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  static const uint8_t kJpeg[3] = {0xff, 0xd8, 0xff};
  uint8_t head[8] = {};
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return false;
  const size_t got = std::fread(head, 1, sizeof(head), file);
  std::fclose(file);
  return (got >= 8 && std::equal(kPng, kPng + 8, head)) ||
         (got >= 3 && std::equal(kJpeg, kJpeg + 3, head));
}

ImageRGBA32F readLdr(const std::string& path) {
  if (!hasPngOrJpegSignature(path))
    fail("{}: not a PNG or JPEG file (it starts with neither signature)", path);
  int width = 0, height = 0, channels = 0;
  if (!stbi_info(path.c_str(), &width, &height, &channels)) {
    fail("{}: not a readable PNG/JPEG image: {}", path, stbReason());
  }
  requireSaneSize(path, width, height);
  ImageRGBA32F image;
  image.width = width;
  image.height = height;
  image.sourceWasLdr = true;
  // Ask for 4 channels: grey and grey+alpha files are expanded by stb. The float pixels are
  // allocated after a successful decode: a truncated file that claims 128 Mpixel fails first.
  if (stbi_is_16_bit(path.c_str())) {
    stbi_us* samples = stbi_load_16(path.c_str(), &width, &height, &channels, 4);
    if (!samples) fail("{}: cannot decode image (truncated or corrupt?): {}", path, stbReason());
    image.pixels.resize(image.pixelCount() * 4);
    decodeSrgb(samples, image);
    stbi_image_free(samples);
  } else {
    stbi_uc* samples = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (!samples) fail("{}: cannot decode image (truncated or corrupt?): {}", path, stbReason());
    image.pixels.resize(image.pixelCount() * 4);
    decodeSrgb(samples, image);
    stbi_image_free(samples);
  }
  return image;
}

bool isOpaque(const ImageRGBA32F& image) {
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    if (image.pixels[4 * i + 3] < 1.0f) return false;
  }
  return true;
}

uint8_t toByte(float unitValue) {
  // NaN fails both comparisons of std::clamp's contract, so test it explicitly.
  if (!(unitValue > 0.0f)) return 0;
  if (unitValue >= 1.0f) return 255;
  return uint8_t(std::lround(unitValue * 255.0f));
}

}  // namespace

ImageRGBA32F readImage(const std::string& path) {
  requireReadableFile(path);
  if (isHdrExtension(path)) return readExr(path);
  if (isLdrExtension(path)) return readLdr(path);
  fail("{}: unsupported image format '{}' (expected .exr, .png, .jpg or .jpeg)", path,
       imageExtension(path));
}

void writeExr(const std::string& path, const ImageRGBA32F& image, const ImageMetadata& metadata) {
  requireSaneSize(path, image.width, image.height);
  // Channels in (A)BGR order, as EXR viewers expect them (and tinyexr's SaveEXR writes them);
  // the explicit header is what lets string attributes travel with the pixels.
  constexpr std::array<const char*, 4> kNames = {"A", "B", "G", "R"};
  constexpr std::array<int, 4> kSourceChannel = {3, 2, 1, 0};
  std::array<std::vector<float>, 4> planes;
  std::array<unsigned char*, 4> planePointers{};
  std::array<EXRChannelInfo, 4> channels{};
  std::array<int, 4> pixelTypes{};
  for (size_t c = 0; c < 4; ++c) {
    planes[c].resize(image.pixelCount());
    for (size_t i = 0; i < image.pixelCount(); ++i)
      planes[c][i] = image.pixels[4 * i + size_t(kSourceChannel[c])];
    planePointers[c] = reinterpret_cast<unsigned char*>(planes[c].data());
    std::snprintf(channels[c].name, sizeof(channels[c].name), "%s", kNames[c]);
    pixelTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
  }
  std::vector<EXRAttribute> attributes(metadata.size());
  for (size_t i = 0; i < metadata.size(); ++i) {
    std::snprintf(attributes[i].name, sizeof(attributes[i].name), "%s", metadata[i].first.c_str());
    std::snprintf(attributes[i].type, sizeof(attributes[i].type), "string");
    attributes[i].value =
        reinterpret_cast<unsigned char*>(const_cast<char*>(metadata[i].second.data()));
    attributes[i].size = int(metadata[i].second.size());
  }
  EXRImage exr;
  InitEXRImage(&exr);
  exr.images = planePointers.data();
  exr.width = image.width;
  exr.height = image.height;
  exr.num_channels = 4;
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = 4;
  header.channels = channels.data();
  header.pixel_types = pixelTypes.data();
  header.requested_pixel_types = pixelTypes.data();
  // tinyexr's own rule (SaveEXR): tiny images uncompressed.
  header.compression_type = image.width < 16 && image.height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE
                                                                  : TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_custom_attributes = int(attributes.size());
  header.custom_attributes = attributes.empty() ? nullptr : attributes.data();
  const char* message = nullptr;
  if (SaveEXRImageToFile(&exr, &header, path.c_str(), &message) != TINYEXR_SUCCESS)
    fail("{}: cannot write EXR: {}", path, takeExrMessage(message));
}

ImageMetadata readExrMetadata(const std::string& path) {
  requireReadableFile(path);
  checkExrHeader(path);
  EXRVersion version;
  ParseEXRVersionFromFile(&version, path.c_str());
  EXRHeader header;
  InitEXRHeader(&header);
  const char* message = nullptr;
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &message) != TINYEXR_SUCCESS) {
    FreeEXRHeader(&header);
    fail("{}: invalid EXR header: {}", path, takeExrMessage(message));
  }
  ImageMetadata metadata;
  for (int i = 0; i < header.num_custom_attributes; ++i) {
    const EXRAttribute& a = header.custom_attributes[i];
    if (std::string(a.type) == "string")
      metadata.emplace_back(a.name,
                            std::string(reinterpret_cast<const char*>(a.value), size_t(a.size)));
  }
  FreeEXRHeader(&header);
  return metadata;
}

void writePng(const std::string& path, const ImageRGBA32F& image, float exposure) {
  requireSaneSize(path, image.width, image.height);
  const int channels = isOpaque(image) ? 3 : 4;
  std::vector<uint8_t> bytes(image.pixelCount() * channels);
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = &image.pixels[4 * i];
    for (int c = 0; c < 3; ++c) bytes[channels * i + c] = toByte(linearToSrgb(p[c] * exposure));
    if (channels == 4) bytes[channels * i + 3] = toByte(p[3]);  // alpha stays linear
  }
  if (!stbi_write_png(path.c_str(), image.width, image.height, channels, bytes.data(),
                      image.width * channels)) {
    fail("{}: cannot write PNG (does the directory exist and is it writable?)", path);
  }
}

void writeImage(const std::string& path, const ImageRGBA32F& image, float exposure,
                const ImageMetadata& metadata) {
  if (isHdrExtension(path)) return writeExr(path, image, metadata);
  if (imageExtension(path) == "png") return writePng(path, image, exposure);
  fail("{}: cannot write images of type '{}' (use .exr or .png)", path, imageExtension(path));
}

}  // namespace bounce
