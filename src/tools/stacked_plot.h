// A stacked-area plot of series over a common x axis, or stacked bars (one per run), (per-pass GPU
// times over a benchmark run, `bounce bench`), written by our own small writers: SVG text, and a
// raster image for PNG (the bench runs on machines with nothing but the program installed, so no
// plotting library).
#pragma once
#include <string>
#include <vector>

#include "tools/image_io.h"

namespace bounce {

struct PlotSeries {
  std::string name;
  std::vector<double> values;  // one per x sample; negative values count as 0
};

struct StackedPlot {
  std::string title;
  std::string xLabel;  // the x axis runs over the sample index 0 .. n-1
  std::string yLabel;
  std::vector<PlotSeries> series;  // bottom to top; all of the same length (>= 1)
  // When given (one name per sample), the plot is a stacked bar chart instead: one bar per sample,
  // named on the x axis (runs side by side: `bounce bench`'s comparison of GI modes, presets,
  // GPUs).
  std::vector<std::string> bars;
  // Samples drawn on a grey background (the bench's night: the sun below the horizon); empty or
  // of the series' length.
  std::vector<bool> shaded;
  std::string shadedLabel;  // its legend entry
  int width = 960;          // pixels (SVG user units)
  int height = 480;
};

// The SVG document: one polygon per series between its lower and upper cumulative curves,
// axes with ticks, and a legend (top series first, as stacked).
std::string stackedPlotSvg(const StackedPlot& plot);
// The same plot rasterised (linear RGBA, for writePng): each pixel column is filled between the
// cumulative curves, linearly interpolated between samples; text from stb_easy_font.
ImageRGBA32F stackedPlotImage(const StackedPlot& plot);

// A one-line label on an image (stb_easy_font's 6-pixel-wide letters), black on a white box so
// that it reads on any picture; (x, y) is the box's top-left corner. For the bench's contact
// sheet.
void drawLabel(ImageRGBA32F& image, int x, int y, const std::string& text);

}  // namespace bounce
