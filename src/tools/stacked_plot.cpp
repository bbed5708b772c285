#include "tools/stacked_plot.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace bounce {

namespace {

// Twelve distinguishable sRGB colours, cycled for more series.
constexpr uint32_t kPalette[] = {0x3b75af, 0xef8636, 0x519e3e, 0xc53a32, 0x8d69b8, 0x84584e,
                                 0xd57dbe, 0x7f7f7f, 0xbcbc45, 0x58bbcc, 0xaec7e8, 0xffbb78};
constexpr int kPaletteSize = int(sizeof(kPalette) / sizeof(kPalette[0]));

uint32_t seriesColour(size_t i) {
  return kPalette[i % kPaletteSize];
}

// The smallest of 1, 2, 2.5, 5, 10 x 10^k at or above v: an axis top that reads well.
double niceCeil(double v) {
  if (!(v > 0.0)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (double step : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (step * decade >= v * (1.0 - 1e-9)) return step * decade;
  return 10.0 * decade;
}

std::string tickLabel(double v) {
  return fmt::format("{:g}", std::round(v * 1000.0) / 1000.0);
}

// Where the plot area lies and how data maps onto it; shared by both writers so that the SVG
// and the PNG show the same picture.
struct Layout {
  double left = 64, top = 48, right = 0, bottom = 0;  // plot area in pixels
  size_t samples = 0;
  bool bars = false;  // StackedPlot::bars given: sample i is a bar in the middle of slot i
  double yMax = 1.0;
  // cumulative[k][i]: the sum of series 0..k-1 at sample i (cumulative[0] is all zero).
  std::vector<std::vector<double>> cumulative;

  double x(double sample) const {
    if (bars) return left + (right - left) * (sample + 0.5) / double(samples);
    return samples < 2 ? left : left + (right - left) * sample / double(samples - 1);
  }
  double barHalfWidth() const { return 0.3 * (right - left) / double(samples); }
  double y(double value) const { return bottom - (bottom - top) * value / yMax; }
};

Layout layoutOf(const StackedPlot& plot) {
  if (plot.series.empty() || plot.series[0].values.empty())
    fail("stacked plot '{}': no series or no samples", plot.title);
  Layout l;
  l.samples = plot.series[0].values.size();
  for (const PlotSeries& s : plot.series)
    if (s.values.size() != l.samples)
      fail("stacked plot '{}': series '{}' has {} samples, expected {}", plot.title, s.name,
           s.values.size(), l.samples);
  if (!plot.shaded.empty() && plot.shaded.size() != l.samples)
    fail("stacked plot '{}': {} shaded flags for {} samples", plot.title, plot.shaded.size(),
         l.samples);
  if (!plot.bars.empty() && plot.bars.size() != l.samples)
    fail("stacked plot '{}': {} bar names for {} samples", plot.title, plot.bars.size(), l.samples);
  l.bars = !plot.bars.empty();
  l.right = plot.width - 250.0;                     // the legend's column
  l.bottom = plot.height - (l.bars ? 72.0 : 44.0);  // bar names may take two or three lines
  l.cumulative.assign(plot.series.size() + 1, std::vector<double>(l.samples, 0.0));
  double top = 0.0;
  for (size_t k = 0; k < plot.series.size(); ++k)
    for (size_t i = 0; i < l.samples; ++i) {
      const double v = plot.series[k].values[i];
      l.cumulative[k + 1][i] = l.cumulative[k][i] + (std::isfinite(v) && v > 0.0 ? v : 0.0);
      top = std::max(top, l.cumulative[k + 1][i]);
    }
  l.yMax = niceCeil(top);
  return l;
}

// x positions of the axis ticks: about six, on whole samples.
std::vector<size_t> xTicks(size_t samples, bool bars) {
  if (bars) {
    std::vector<size_t> all(samples);
    for (size_t i = 0; i < samples; ++i) all[i] = i;
    return all;
  }
  const size_t step = std::max<size_t>(1, size_t(niceCeil(double(samples) / 6.0)));
  std::vector<size_t> ticks;
  for (size_t i = 0; i < samples; i += step) ticks.push_back(i);
  return ticks;
}

constexpr int kYTicks = 5;
constexpr uint32_t kShadeColour = 0xdddddd;

// Sample i's shaded flag covers x from halfway to its left neighbour to halfway to its right.
bool shadedAt(const StackedPlot& plot, const Layout& l, double sample) {
  if (plot.shaded.empty()) return false;
  return plot.shaded[std::min(l.samples - 1, size_t(std::max(0.0, std::round(sample))))];
}

std::string xTickLabel(const StackedPlot& plot, size_t i) {
  return plot.bars.empty() ? std::to_string(i) : plot.bars[i];
}

std::vector<std::string> legendNames(const StackedPlot& plot) {
  std::vector<std::string> names;
  for (size_t k = plot.series.size(); k-- > 0;) names.push_back(plot.series[k].name);
  if (!plot.shaded.empty()) names.push_back(plot.shadedLabel);
  return names;
}

// ---- SVG ----

std::string escapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string hex(uint32_t rgb) {
  return fmt::format("#{:06x}", rgb);
}

// Text with '\n' as SVG lines at x: the first at the text's y, each next one 14 units lower.
std::string svgLines(const std::string& text, double x) {
  std::string out;
  size_t start = 0;
  for (int line = 0;; ++line) {
    const size_t end = text.find('\n', start);
    const std::string part = escapeXml(text.substr(start, end - start));
    out += line == 0 ? part : fmt::format("<tspan x=\"{:.1f}\" dy=\"14\">{}</tspan>", x, part);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

std::string stackedPlotSvg(const StackedPlot& plot) {
  const Layout l = layoutOf(plot);
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      plot.width, plot.height);
  for (size_t i = 0; i < plot.shaded.size(); ++i)
    if (plot.shaded[i]) {
      const double x0 = std::max(l.left, l.x(double(i) - 0.5));
      const double x1 = std::min(l.right, l.x(double(i) + 0.5));
      svg += fmt::format(
          "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\"/>\n", x0,
          l.top, x1 - x0, l.bottom - l.top, hex(kShadeColour));
    }
  // Bars: one rectangle per series and bar.
  for (size_t k = 0; l.bars && k < plot.series.size(); ++k)
    for (size_t i = 0; i < l.samples; ++i)
      svg += fmt::format(
          "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\">"
          "<title>{}: {:.3f}</title></rect>\n",
          l.x(double(i)) - l.barHalfWidth(), l.y(l.cumulative[k + 1][i]), 2 * l.barHalfWidth(),
          l.y(l.cumulative[k][i]) - l.y(l.cumulative[k + 1][i]), hex(seriesColour(k)),
          escapeXml(plot.series[k].name), plot.series[k].values[i]);
  // Areas: one polygon per series, along its upper curve, back along the lower one.
  for (size_t k = 0; !l.bars && k < plot.series.size(); ++k) {
    std::string points;
    for (size_t i = 0; i < l.samples; ++i)
      points += fmt::format("{:.1f},{:.1f} ", l.x(double(i)), l.y(l.cumulative[k + 1][i]));
    for (size_t i = l.samples; i-- > 0;)
      points += fmt::format("{:.1f},{:.1f} ", l.x(double(i)), l.y(l.cumulative[k][i]));
    svg += fmt::format("<polygon fill=\"{}\" points=\"{}\"><title>{}</title></polygon>\n",
                       hex(seriesColour(k)), points, escapeXml(plot.series[k].name));
  }
  svg += fmt::format(
      "<path d=\"M{0:.1f},{1:.1f} V{2:.1f} H{3:.1f}\" stroke=\"black\" fill=\"none\"/>\n", l.left,
      l.top, l.bottom, l.right);
  for (int t = 0; t <= kYTicks; ++t) {
    const double v = l.yMax * t / kYTicks;
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" x2=\"{1:.1f}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"black\"/>"
        "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
        l.left - 4, l.left, l.y(v), l.left - 6, l.y(v) + 4, tickLabel(v));
  }
  for (size_t i : xTicks(l.samples, l.bars))
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1:.1f}\" y2=\"{2:.1f}\" stroke=\"black\"/>"
        "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\">{4}</text>\n",
        l.x(double(i)), l.bottom, l.bottom + 4, l.bottom + 17,
        svgLines(xTickLabel(plot, i), l.x(double(i))));
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     (l.left + l.right) / 2, plot.height - 8, escapeXml(plot.xLabel));
  svg +=
      fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", 8, l.top - 12, escapeXml(plot.yLabel));
  svg +=
      fmt::format("<text x=\"{:.1f}\" y=\"18\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
                  (l.left + l.right) / 2, escapeXml(plot.title));
  // The legend reads top to bottom as the stack does, the shading last.
  const std::vector<std::string> names = legendNames(plot);
  for (size_t row = 0; row < names.size(); ++row) {
    const size_t k = plot.series.size() - 1 - row;
    const double y = l.top + 16.0 * double(row);
    svg += fmt::format(
        "<rect x=\"{0:.1f}\" y=\"{1:.1f}\" width=\"12\" height=\"12\" fill=\"{2}\"/>"
        "<text x=\"{3:.1f}\" y=\"{4:.1f}\">{5}</text>\n",
        l.right + 12, y, hex(row < plot.series.size() ? seriesColour(k) : kShadeColour),
        l.right + 30, y + 10, escapeXml(names[row]));
  }
  svg += "</svg>\n";
  return svg;
}

namespace {

// ---- raster ----

glm::vec4 linearColour(uint32_t rgb) {
  auto channel = [&](int shift) { return srgbToLinear(float((rgb >> shift) & 0xff) / 255.0f); };
  return {channel(16), channel(8), channel(0), 1.0f};
}

void fillRect(ImageRGBA32F& image, double x0, double y0, double x1, double y1,
              const glm::vec4& colour) {
  const int xa = std::max(0, int(std::lround(x0))),
            xb = std::min(image.width, int(std::lround(x1)));
  const int ya = std::max(0, int(std::lround(y0)));
  const int yb = std::min(image.height, int(std::lround(y1)));
  for (int y = ya; y < yb; ++y)
    for (int x = xa; x < xb; ++x) image.set(x, y, colour);
}

// stb_easy_font draws text as axis-aligned quads (4 vertices of 16 bytes each), which we fill.
// `anchor`: 0 left, 0.5 centred, 1 right-aligned at x.
void drawText(ImageRGBA32F& image, double x, double y, const std::string& text,
              double anchor = 0.0) {
  std::vector<char> chars(text.begin(), text.end());
  chars.push_back('\0');
  x -= anchor * stb_easy_font_width(chars.data());
  std::vector<char> buffer(300 * chars.size() + 1024);
  const int quads = stb_easy_font_print(float(x), float(y), chars.data(), nullptr, buffer.data(),
                                        int(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    const float* v = reinterpret_cast<const float*>(buffer.data() + 64 * q);
    // Vertices 0 and 2 are opposite corners (x, y at float offsets 0, 1 and 8, 9).
    fillRect(image, v[0], v[1], v[8], v[9], glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  }
}

}  // namespace

ImageRGBA32F stackedPlotImage(const StackedPlot& plot) {
  const Layout l = layoutOf(plot);
  ImageRGBA32F image(plot.width, plot.height, glm::vec4(1.0f));
  // Column by column: the data at this x (interpolated between the two nearest samples), then
  // each series' span between its lower and upper cumulative values.
  for (size_t k = 0; l.bars && k < plot.series.size(); ++k)
    for (size_t i = 0; i < l.samples; ++i)
      fillRect(image, l.x(double(i)) - l.barHalfWidth(), l.y(l.cumulative[k + 1][i]),
               l.x(double(i)) + l.barHalfWidth(), l.y(l.cumulative[k][i]),
               linearColour(seriesColour(k)));
  for (int px = int(std::ceil(l.left)); !l.bars && px < int(l.right); ++px) {
    const double s = l.samples < 2 ? 0.0 : (px - l.left) / (l.right - l.left) * (l.samples - 1);
    const size_t i0 = std::min(size_t(s), l.samples - 1), i1 = std::min(i0 + 1, l.samples - 1);
    const double f = s - double(i0);
    if (shadedAt(plot, l, s))
      fillRect(image, px, l.top, px + 1, l.bottom, linearColour(kShadeColour));
    for (size_t k = 0; k < plot.series.size(); ++k) {
      const double lo = (1 - f) * l.cumulative[k][i0] + f * l.cumulative[k][i1];
      const double hi = (1 - f) * l.cumulative[k + 1][i0] + f * l.cumulative[k + 1][i1];
      fillRect(image, px, l.y(hi), px + 1, l.y(lo), linearColour(seriesColour(k)));
    }
  }
  const glm::vec4 black(0.0f, 0.0f, 0.0f, 1.0f);
  fillRect(image, l.left - 1, l.top, l.left, l.bottom + 1, black);
  fillRect(image, l.left - 1, l.bottom, l.right, l.bottom + 1, black);
  for (int t = 0; t <= kYTicks; ++t) {
    const double v = l.yMax * t / kYTicks, y = l.y(v);
    fillRect(image, l.left - 5, y, l.left - 1, y + 1, black);
    drawText(image, l.left - 8, y - 3, tickLabel(v), 1.0);
  }
  for (size_t i : xTicks(l.samples, l.bars)) {
    const double x = l.x(double(i));
    fillRect(image, x, l.bottom, x + 1, l.bottom + 5, black);
    drawText(image, x, l.bottom + 9, xTickLabel(plot, i), 0.5);
  }
  drawText(image, (l.left + l.right) / 2, plot.height - 16, plot.xLabel, 0.5);
  drawText(image, 8, l.top - 20, plot.yLabel);
  drawText(image, (l.left + l.right) / 2, 8, plot.title, 0.5);
  const std::vector<std::string> names = legendNames(plot);
  for (size_t row = 0; row < names.size(); ++row) {
    const size_t k = plot.series.size() - 1 - row;
    const double y = l.top + 16.0 * double(row);
    fillRect(image, l.right + 12, y, l.right + 24, y + 12,
             linearColour(row < plot.series.size() ? seriesColour(k) : kShadeColour));
    drawText(image, l.right + 30, y + 2, names[row]);
  }
  return image;
}

void drawLabel(ImageRGBA32F& image, int x, int y, const std::string& text) {
  std::vector<char> chars(text.begin(), text.end());
  chars.push_back('\0');
  fillRect(image, x, y, x + stb_easy_font_width(chars.data()) + 4, y + 12, glm::vec4(1.0f));
  drawText(image, x + 2, y + 2, text);
}

}  // namespace bounce
