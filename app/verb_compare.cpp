// `bounce compare TEST REF`: relMSE, MSE, PSNR and FLIP of a test image against a reference
// (DESIGN.md §6), as a table on stdout, optionally as JSON and as a FLIP heat map.
#include <cstdio>
#include <memory>

#include "tools/compare.h"
#include "verbs.h"

namespace bounce::app {

void addCompareVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* verb = app.add_subcommand(
      "compare",
      "Compare a test image with a reference: relMSE, MSE, PSNR and FLIP (LDR-FLIP for PNG/JPG "
      "pairs, HDR-FLIP for EXR pairs)");
  verb->add_option("test", options->testPath, "Test image (.png, .jpg or .exr)")->required();
  verb->add_option("reference", options->referencePath, "Reference image of the same size and kind")
      ->required();
  verb->add_option("--json", options->jsonPath, "Also write the metrics to this JSON file");
  verb->add_option("--heatmap", options->heatmapPath, "Write the FLIP error map as a colour PNG");
  verb->add_option("--side-by-side", options->sideBySidePath,
                   "Write test | reference | FLIP heat map side by side as one PNG");
  verb->add_option("--exposure", options->exposureStops,
                   "Side-by-side of EXR pairs: scale by 2^STOPS (default: the reference's 99th "
                   "percentile luminance at white)");
  verb->add_option("--zoom", options->zoom, "Side-by-side: enlarge each pixel N times (1-16)")
      ->capture_default_str();
  verb->add_option("--ppd", options->pixelsPerDegree,
                   "Observer's pixels per degree of visual angle (FLIP tool default: 0.7 m wide "
                   "4K screen at 0.7 m)")
      ->check(CLI::Range(0.1f, 1000.0f))
      ->capture_default_str();
  verb->callback([options, &action] {
    action = [options] {
      const CompareReport report = runCompare(*options);
      std::fputs(formatCompareTable(report).c_str(), stdout);
      return 0;
    };
  });
}

}  // namespace bounce::app
