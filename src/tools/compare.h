// `bounce compare`: a test image against a reference, with every metric of tools/metrics.h.
// PNG/JPG pairs get LDR-FLIP and sRGB PSNR; EXR pairs get HDR-FLIP and linear PSNR; mixing the
// two is refused, because an sRGB picture and scene-referred radiance are not comparable without
// choosing a tone mapping first.
#pragma once
#include <cmath>
#include <optional>
#include <string>

#include "tools/flip.h"
#include "tools/metrics.h"

namespace bounce {

struct ImageRGBA32F;

struct CompareOptions {
  std::string testPath;
  std::string referencePath;
  float pixelsPerDegree = kDefaultPixelsPerDegree;
  std::string jsonPath;     // empty: no JSON report
  std::string heatmapPath;  // empty: no heat map (.png)
  // Test | reference | FLIP heat map in one PNG, each enlarged `zoom` times (nearest), for
  // looking at a pair. HDR pairs are scaled by 2^exposureStops; NaN = pick the exposure that puts
  // the reference's 99th-percentile luminance at white.
  std::string sideBySidePath;
  float exposureStops = NAN;
  int zoom = 1;
  // The reference at an earlier pose of a moving scene (tools/metrics.h trailMask): also report
  // the error inside the region that changed since and outside it. Empty: no trail report.
  std::string trailReferencePath;
};

struct CompareReport {
  std::string testPath;
  std::string referencePath;
  int width = 0;
  int height = 0;
  bool hdr = false;  // EXR pair: HDR-FLIP, linear PSNR
  double mse = 0.0;
  double relMse = 0.0;
  double psnrDb = 0.0;  // +infinity for identical images
  float pixelsPerDegree = kDefaultPixelsPerDegree;
  FlipResult flip;
  double flipSeconds = 0.0;
  std::string trailReferencePath;
  std::optional<TrailError> trail;  // with CompareOptions::trailReferencePath
};

// Reads both images and computes the metrics, and with `trailReferencePath` the trail's
// (CompareOptions::trailReferencePath). Throws bounce::Error naming the file for unreadable
// images, different sizes, an LDR/HDR mix, or NaN/infinite pixels.
CompareReport compareImages(const std::string& testPath, const std::string& referencePath,
                            float pixelsPerDegree = kDefaultPixelsPerDegree,
                            const std::string& trailReferencePath = "");

// The human-readable table `bounce compare` prints.
std::string formatCompareTable(const CompareReport& report);
// The same fields as JSON text (see compare.cpp for the keys).
std::string compareReportJson(const CompareReport& report);

// The exposure (a multiplier) that maps the 99th-percentile luminance of `image` to 1.
float autoExposure(const ImageRGBA32F& image);

// compareImages, then the JSON report, heat map and side-by-side picture the options ask for.
CompareReport runCompare(const CompareOptions& options);

}  // namespace bounce
