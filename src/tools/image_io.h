// Reading and writing the images Bounce compares and produces. In memory every image is linear
// RGBA float, rows top to bottom; `sourceWasLdr` remembers whether the file was 8-bit display
// sRGB (PNG/JPG, decoded to linear on load) or scene-referred linear (EXR), because the metrics
// treat the two differently (LDR-FLIP vs HDR-FLIP).
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

namespace bounce {

struct ImageRGBA32F {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // RGBA, linear, rows top to bottom
  bool sourceWasLdr = false;  // decoded from 8/16-bit sRGB (PNG/JPG) rather than EXR

  ImageRGBA32F() = default;
  ImageRGBA32F(int width, int height, glm::vec4 fill = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));

  size_t pixelCount() const { return size_t(width) * size_t(height); }
  float* pixel(int x, int y) { return pixels.data() + 4 * (size_t(y) * width + x); }
  const float* pixel(int x, int y) const { return pixels.data() + 4 * (size_t(y) * width + x); }
  glm::vec4 at(int x, int y) const;
  void set(int x, int y, const glm::vec4& rgba);
};

// Largest image we accept (either side, and in total): anything bigger is treated as a corrupt
// or hostile file rather than allocated.
constexpr int kMaxImageSide = 32768;
constexpr size_t kMaxImagePixels = size_t(1) << 27;  // 128 Mpixel = 2 GiB as RGBA32F

// sRGB transfer functions (IEC 61966-2-1), one channel.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// .exr (tinyexr: linear scene-referred float) or .png/.jpg/.jpeg (stb: 8- or 16-bit sRGB,
// decoded to linear). Throws bounce::Error naming the file and the problem: missing,
// unreadable, truncated, not the format its extension says, or absurdly large.
ImageRGBA32F readImage(const std::string& path);

// Name/value text stored with an image: EXR "string" attributes (e.g. the samples per pixel of
// an interrupted reference render). PNG files do not carry it (stb writes no text chunks).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// 32-bit float RGBA EXR (ZIP compressed), with `metadata` as string attributes.
void writeExr(const std::string& path, const ImageRGBA32F& image,
              const ImageMetadata& metadata = {});
// The string attributes of an EXR file's header.
ImageMetadata readExrMetadata(const std::string& path);
// 8-bit sRGB PNG: linear * exposure -> clamp to [0,1] -> sRGB OETF, no tone curve (the same
// as Cycles' "Standard" view transform). RGB when every alpha is 1, RGBA otherwise.
void writePng(const std::string& path, const ImageRGBA32F& image, float exposure = 1.0f);
// Picks writeExr or writePng by extension (exposure applies to PNG only, metadata to EXR only).
void writeImage(const std::string& path, const ImageRGBA32F& image, float exposure = 1.0f,
                const ImageMetadata& metadata = {});

// Lower-case extension without the dot ("exr", "png"), empty when there is none.
std::string imageExtension(const std::string& path);
bool isHdrExtension(const std::string& path);  // exr
bool isLdrExtension(const std::string& path);  // png, jpg, jpeg

}  // namespace bounce
