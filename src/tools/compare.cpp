#include "tools/compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tools/heatmap.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "tools/output_file.h"

namespace bounce {
namespace {

std::string describeKind(bool ldr) {
  return ldr ? "an LDR image (8-bit sRGB PNG/JPG)" : "an HDR image (linear EXR)";
}

void requireComparable(const std::string& testPath, const ImageRGBA32F& test,
                       const std::string& referencePath, const ImageRGBA32F& reference) {
  if (test.sourceWasLdr != reference.sourceWasLdr) {
    fail(
        "{} is {} but {} is {}: compare PNG/JPG with PNG/JPG (LDR-FLIP) or EXR with EXR "
        "(HDR-FLIP); a display-referred picture and scene-referred radiance differ by a tone "
        "mapping, so their difference would not mean anything",
        testPath, describeKind(test.sourceWasLdr), referencePath,
        describeKind(reference.sourceWasLdr));
  }
  if (test.width != reference.width || test.height != reference.height) {
    fail("{} is {}x{} but {} is {}x{}: the images must have the same size", testPath, test.width,
         test.height, referencePath, reference.width, reference.height);
  }
}

void requireFinite(const std::string& path, const ImageRGBA32F& image) {
  if (const size_t bad = countNonFinitePixels(image)) {
    fail("{}: {} pixel(s) have NaN or infinite values; metrics would be meaningless", path, bad);
  }
}

// JSON has no infinity; an exact match reports PSNR as null.
nlohmann::json finiteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

std::string formatPsnr(const CompareReport& report) {
  const std::string basis = report.hdr ? "linear, peak = reference max" : "sRGB, peak 1";
  if (!std::isfinite(report.psnrDb)) return fmt::format("inf dB ({}; identical)", basis);
  return fmt::format("{:.2f} dB ({})", report.psnrDb, basis);
}

}  // namespace

CompareReport compareImages(const std::string& testPath, const std::string& referencePath,
                            float pixelsPerDegree, const std::string& trailReferencePath) {
  const ImageRGBA32F test = readImage(testPath);
  const ImageRGBA32F reference = readImage(referencePath);
  requireComparable(testPath, test, referencePath, reference);
  requireFinite(testPath, test);
  requireFinite(referencePath, reference);

  CompareReport report;
  report.testPath = testPath;
  report.referencePath = referencePath;
  report.width = test.width;
  report.height = test.height;
  report.hdr = !reference.sourceWasLdr;
  report.pixelsPerDegree = pixelsPerDegree;
  report.mse = meanSquaredError(test, reference);
  report.relMse = relativeMeanSquaredError(test, reference);
  report.psnrDb = report.hdr ? psnrHdr(test, reference) : psnrLdr(test, reference);
  const auto start = std::chrono::steady_clock::now();
  report.flip = report.hdr ? computeHdrFlip(test, reference, pixelsPerDegree)
                           : computeLdrFlip(test, reference, pixelsPerDegree);
  report.flipSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!trailReferencePath.empty()) {
    const ImageRGBA32F earlier = readImage(trailReferencePath);
    requireComparable(trailReferencePath, earlier, referencePath, reference);
    requireFinite(trailReferencePath, earlier);
    report.trailReferencePath = trailReferencePath;
    report.trail = trailError(test, reference, trailMask(reference, earlier));
  }
  return report;
}

std::string formatCompareTable(const CompareReport& r) {
  const FlipStatistics& s = r.flip.statistics;
  std::string out = fmt::format("test       {}\nreference  {}\n", r.testPath, r.referencePath);
  out += fmt::format("size       {}x{}, {} at {:.2f} pixels/degree\n\n", r.width, r.height,
                     r.hdr ? "HDR-FLIP" : "LDR-FLIP", r.pixelsPerDegree);
  const auto row = [&out](const char* name, const std::string& value) {
    out += fmt::format("  {:<28}{}\n", name, value);
  };
  row("relMSE", fmt::format("{:.6f} (epsilon {})", r.relMse, kRelMseEpsilon));
  row("MSE", fmt::format("{:.6e} (linear)", r.mse));
  row("PSNR", formatPsnr(r));
  row("FLIP mean", fmt::format("{:.6f}", s.mean));
  row("FLIP weighted median", fmt::format("{:.6f}", s.weightedMedian));
  row("FLIP 1st weighted quartile", fmt::format("{:.6f}", s.firstWeightedQuartile));
  row("FLIP 3rd weighted quartile", fmt::format("{:.6f}", s.thirdWeightedQuartile));
  row("FLIP min", fmt::format("{:.6f}", s.min));
  row("FLIP max", fmt::format("{:.6f}", s.max));
  if (r.flip.exposures) {
    const FlipExposureRange& e = *r.flip.exposures;
    row("HDR-FLIP exposures",
        fmt::format("{:.4f} to {:.4f} stops, {} steps, ACES", e.start, e.stop, e.count));
  }
  row("FLIP time", fmt::format("{:.3f} s", r.flipSeconds));
  if (r.trail) {
    const TrailError& t = *r.trail;
    out += fmt::format("\ntrail      the pixels that changed since {}\n", r.trailReferencePath);
    row("trail pixels", fmt::format("{} ({:.2f} %)", t.pixels,
                                    100.0 * double(t.pixels) / double(r.width * r.height)));
    row("relMSE in the trail", fmt::format("{:.6f}", t.relMseTrail));
    row("relMSE elsewhere", fmt::format("{:.6f}", t.relMseRest));
    row("trail luminance ratio", fmt::format("{:.4f} (test / reference)", t.luminanceRatio));
  }
  return out;
}

std::string compareReportJson(const CompareReport& r) {
  const FlipStatistics& s = r.flip.statistics;
  nlohmann::json flip = {{"mean", s.mean},
                         {"weighted_median", s.weightedMedian},
                         {"first_weighted_quartile", s.firstWeightedQuartile},
                         {"third_weighted_quartile", s.thirdWeightedQuartile},
                         {"min", s.min},
                         {"max", s.max},
                         {"pixels_per_degree", r.pixelsPerDegree},
                         {"seconds", r.flipSeconds}};
  if (r.flip.exposures) {
    flip["tone_mapper"] = "aces";
    flip["exposure_start"] = r.flip.exposures->start;
    flip["exposure_stop"] = r.flip.exposures->stop;
    flip["exposure_count"] = r.flip.exposures->count;
  }
  nlohmann::json report = {{"test", r.testPath},
                           {"reference", r.referencePath},
                           {"width", r.width},
                           {"height", r.height},
                           {"mode", r.hdr ? "hdr" : "ldr"},
                           {"rel_mse", r.relMse},
                           {"rel_mse_epsilon", kRelMseEpsilon},
                           {"mse", r.mse},
                           {"psnr_db", finiteOrNull(r.psnrDb)},
                           {"flip", flip}};
  if (r.trail)
    report["trail"] = {{"earlier_reference", r.trailReferencePath},
                       {"pixels", r.trail->pixels},
                       {"rel_mse_trail", r.trail->relMseTrail},
                       {"rel_mse_rest", r.trail->relMseRest},
                       {"luminance_ratio", r.trail->luminanceRatio}};
  // Paths are bytes, not always UTF-8: an invalid sequence becomes U+FFFD rather than an
  // exception, so the report is always valid JSON.
  return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

float autoExposure(const ImageRGBA32F& image) {
  std::vector<float> luminance;
  luminance.reserve(image.pixelCount());
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = image.pixels.data() + 4 * i;
    luminance.push_back(0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]);
  }
  if (luminance.empty()) return 1.0f;
  const size_t rank = std::min(luminance.size() - 1, size_t(0.99 * double(luminance.size())));
  std::nth_element(luminance.begin(), luminance.begin() + rank, luminance.end());
  const float high = luminance[rank];
  return high > 0.0f && std::isfinite(high) ? 1.0f / high : 1.0f;
}

namespace {

// Copies `source` into `target` at column offset `x0`, each pixel a zoom x zoom block.
void pasteZoomed(ImageRGBA32F& target, const ImageRGBA32F& source, int x0, int zoom) {
  for (int y = 0; y < source.height * zoom; ++y)
    for (int x = 0; x < source.width * zoom; ++x)
      target.set(x0 + x, y, source.at(x / zoom, y / zoom));
}

void writeSideBySide(const CompareOptions& options, const CompareReport& report) {
  ImageRGBA32F test = readImage(options.testPath);
  ImageRGBA32F reference = readImage(options.referencePath);
  if (report.hdr) {  // scale radiance; PNG pairs are already display-referred
    const float scale = std::isnan(options.exposureStops) ? autoExposure(reference)
                                                          : std::exp2(options.exposureStops);
    for (ImageRGBA32F* image : {&test, &reference})
      for (size_t i = 0; i < image->pixels.size(); ++i)
        if (i % 4 != 3) image->pixels[i] *= scale;
  }
  ImageRGBA32F heat(report.width, report.height);
  for (int y = 0; y < report.height; ++y)
    for (int x = 0; x < report.width; ++x) {
      const glm::vec3 c = heatmapColor(report.flip.errorMap[size_t(y) * report.width + x]);
      heat.set(x, y, glm::vec4(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z), 1.0f));
    }
  const int zoom = options.zoom;
  const int gap = 4;
  ImageRGBA32F out(3 * report.width * zoom + 2 * gap, report.height * zoom, glm::vec4(1.0f));
  pasteZoomed(out, test, 0, zoom);
  pasteZoomed(out, reference, report.width * zoom + gap, zoom);
  pasteZoomed(out, heat, 2 * (report.width * zoom + gap), zoom);
  writePng(options.sideBySidePath, out);
}

}  // namespace

CompareReport runCompare(const CompareOptions& options) {
  for (const std::string* path : {&options.heatmapPath, &options.sideBySidePath}) {
    if (!path->empty() && imageExtension(*path) != "png") {
      fail("{}: this picture is written as PNG; give it a .png name", *path);
    }
  }
  if (options.zoom < 1 || options.zoom > 16) fail("--zoom {}: expected 1 to 16", options.zoom);
  CompareReport report = compareImages(options.testPath, options.referencePath,
                                       options.pixelsPerDegree, options.trailReferencePath);
  if (!options.heatmapPath.empty()) writeHeatmap(options.heatmapPath, report.flip);
  if (!options.sideBySidePath.empty()) writeSideBySide(options, report);
  if (!options.jsonPath.empty()) writeTextFile(options.jsonPath, compareReportJson(report));
  return report;
}

}  // namespace bounce
