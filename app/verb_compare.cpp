// `bounce compare TEST REF`: relMSE, MSE, PSNR and FLIP of a test image against a reference
// (DESIGN.md §6), as a table on stdout, optionally as JSON and as a FLIP heat map.
#include <cstdio>
#include <memory>

#include "common_options.h"
#include "core/error.h"
#include "tools/compare.h"
#include "tools/image_io.h"
#include "tools/output_file.h"
#include "verbs.h"

namespace bounce::app {

namespace {

struct CompareVerbOptions {
  CompareOptions compare;
  GivenOptions given;
};

// Every output checked before the images are read and compared.
void checkOutputs(const CompareVerbOptions& options) {
  const CompareOptions& o = options.compare;
  for (const char* option : {"--exposure", "--zoom"})
    if (options.given.has(option) && o.sideBySidePath.empty())
      fail("{} applies to the side-by-side picture only: give --side-by-side FILE.png too", option);
  for (auto [option, path] :
       {std::pair{"--heatmap", &o.heatmapPath}, std::pair{"--side-by-side", &o.sideBySidePath}}) {
    if (path->empty()) continue;
    if (imageExtension(*path) != "png")
      fail("{} '{}': this picture is written as PNG; give it a .png name", option, *path);
    requireWritableFile(option, *path);
  }
  if (!o.jsonPath.empty()) requireWritableFile("--json", o.jsonPath);
}

}  // namespace

void addCompareVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<CompareVerbOptions>();
  CompareOptions& o = options->compare;
  CLI::App* verb = app.add_subcommand(
      "compare",
      "Compare a test image with a reference: relMSE, MSE, PSNR and FLIP (LDR-FLIP for PNG/JPG "
      "pairs, HDR-FLIP for EXR pairs)");
  verb->add_option("test", o.testPath, "Test image (.png, .jpg or .exr)")->required();
  verb->add_option("reference", o.referencePath, "Reference image of the same size and kind")
      ->required();
  verb->add_option("--json", o.jsonPath, "Also write the metrics to this JSON file");
  verb->add_option("--heatmap", o.heatmapPath, "Write the FLIP error map as a colour PNG");
  verb->add_option("--trail", o.trailReferencePath,
                   "The reference at an earlier pose of a moving scene (e.g. 10 frames before): "
                   "also report relMSE inside the pixels that changed since (moving objects' old "
                   "and new places, their shadows) and elsewhere, and the luminance ratio there: "
                   "ghosting and lag (docs/tools.md)");
  verb->add_option("--side-by-side", o.sideBySidePath,
                   "Write test | reference | FLIP heat map side by side as one PNG");
  verb->add_option("--exposure", o.exposureStops,
                   "Side-by-side of EXR pairs: scale by 2^STOPS (default: the reference's 99th "
                   "percentile luminance at white)");
  verb->add_option("--zoom", o.zoom, "Side-by-side: enlarge each pixel N times (1-16)")
      ->capture_default_str();
  verb->add_option("--ppd", o.pixelsPerDegree,
                   "Observer's pixels per degree of visual angle (FLIP tool default: 0.7 m wide "
                   "4K screen at 0.7 m)")
      ->check(CLI::Range(0.1f, 1000.0f))
      ->capture_default_str();
  verb->callback([options, verb, &action] {
    options->given.record(*verb);
    action = [options] {
      checkOutputs(*options);
      const CompareReport report = runCompare(options->compare);
      std::fputs(formatCompareTable(report).c_str(), stdout);
      return 0;
    };
  });
}

}  // namespace bounce::app
