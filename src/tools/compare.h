// `bounce compare`: a test image against a reference, with every metric of tools/metrics.h.
// PNG/JPG pairs get LDR-FLIP and sRGB PSNR; EXR pairs get HDR-FLIP and linear PSNR; mixing the
// two is refused, because an sRGB picture and scene-referred radiance are not comparable without
// choosing a tone mapping first.
#pragma once
#include <string>

#include "tools/flip.h"

namespace bounce {

struct CompareOptions {
  std::string testPath;
  std::string referencePath;
  float pixelsPerDegree = kDefaultPixelsPerDegree;
  std::string jsonPath;     // empty: no JSON report
  std::string heatmapPath;  // empty: no heat map (.png)
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
};

// Reads both images and computes the metrics. Throws bounce::Error naming the file for
// unreadable images, different sizes, an LDR/HDR mix, or NaN/infinite pixels.
CompareReport compareImages(const std::string& testPath, const std::string& referencePath,
                            float pixelsPerDegree = kDefaultPixelsPerDegree);

// The human-readable table `bounce compare` prints.
std::string formatCompareTable(const CompareReport& report);
// The same fields as JSON text (see compare.cpp for the keys).
std::string compareReportJson(const CompareReport& report);

// compareImages, then the JSON report and heat map the options ask for.
CompareReport runCompare(const CompareOptions& options);

}  // namespace bounce
