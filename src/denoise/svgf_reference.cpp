#include "denoise/svgf_reference.h"

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {

struct Grid {
  const SvgfAtrousInput& in;
  bool inside(int x, int y) const {
    return x >= 0 && y >= 0 && x < int(in.width) && y < int(in.height);
  }
  size_t index(int x, int y) const { return size_t(y) * in.width + size_t(x); }
  double depth(int x, int y) const { return in.surface[index(x, y)].w; }
  bool surface(int x, int y) const {
    double z = depth(x, y);
    return inside(x, y) && z > 0.0 && std::isfinite(z);
  }
};

double luminance(const glm::dvec3& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// The kernel's 1-D weight at `offset` (shared/svgf_io.h): B3 spline (1/16, 1/4, 3/8, 1/4, 1/16)
// or RELAX's 3x3 Gaussian (0.27901, 0.44198, 0.27901).
double kernelWeight(SvgfKernel kernel, int offset) {
  static constexpr double kB3[3] = {3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0};
  static constexpr double kGaussian[2] = {0.44198, 0.27901};
  return kernel == SvgfKernel::Gaussian3x3 ? kGaussian[std::abs(offset)] : kB3[std::abs(offset)];
}
int kernelRadius(SvgfKernel kernel) {
  return kernel == SvgfKernel::Gaussian3x3 ? 1 : 2;
}

// The surface's depth change per pixel along an axis: the smaller one-sided difference.
double slopeAlong(const Grid& g, int x, int y, int ax, int ay) {
  double best = -1.0;
  for (int s : {-1, 1})
    if (g.surface(x + s * ax, y + s * ay)) {
      double d = std::abs(g.depth(x + s * ax, y + s * ay) - g.depth(x, y));
      best = best < 0.0 ? d : std::min(best, d);
    }
  return std::max(best, 0.0);
}

// The variance at (x, y) blurred by the 3x3 Gaussian (1/4, 1/2, 1/4)^2 over surface pixels.
double prefilteredVariance(const Grid& g, int x, int y) {
  double sum = 0.0, weights = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!g.surface(x + dx, y + dy)) continue;
      double w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
      sum += w * g.in.colourVariance[g.index(x + dx, y + dy)].w;
      weights += w;
    }
  return sum / weights;
}

// The depth's change per pixel (svgf.slope): the axes' one-sided slopes combined.
double depthSlope(const Grid& g, int x, int y) {
  return std::hypot(slopeAlong(g, x, y, 1, 0), slopeAlong(g, x, y, 0, 1));
}

glm::vec4 filterPixel(const Grid& g, int x, int y, uint32_t iteration, const SvgfSettings& s) {
  const int step = 1 << iteration;
  const glm::dvec4 centre = g.in.colourVariance[g.index(x, y)];
  const glm::dvec3 n = glm::dvec3(g.in.surface[g.index(x, y)]);
  const double z = g.depth(x, y);
  const double l = luminance(glm::dvec3(centre));
  const bool prefilter = iteration == 0 || s.prefilterEveryIteration;
  const double deviation =
      std::sqrt(std::max(prefilter ? prefilteredVariance(g, x, y) : centre.w, 0.0));
  const double slope = depthSlope(g, x, y);
  glm::dvec3 colour(0.0);
  double variance = 0.0, weights = 0.0;
  const int radius = kernelRadius(s.kernel);
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      int qx = x + step * dx, qy = y + step * dy;
      if (!g.surface(qx, qy)) continue;
      const glm::dvec4 c = g.in.colourVariance[g.index(qx, qy)];
      const glm::dvec3 nq = glm::dvec3(g.in.surface[g.index(qx, qy)]);
      double w = kernelWeight(s.kernel, dx) * kernelWeight(s.kernel, dy);
      if (dx != 0 || dy != 0) {
        // Schied eq. 3-5 (depth term with Falcor's |grad z| |offset|; svgf_common.glsl).
        double distance = step * std::hypot(double(dx), double(dy));
        double wz = std::abs(z - g.depth(qx, qy)) / (s.phiDepth * slope * distance + 1e-3 * z);
        double wn = std::pow(std::max(glm::dot(n, nq), 0.0), double(s.phiNormal));
        // SvgfLuminanceStop: the centre's deviation, or its geometric mean with the tap's.
        double scale = s.luminanceStop == SvgfLuminanceStop::Shared
                           ? std::sqrt(deviation * std::sqrt(std::max(c.w, 0.0)))
                           : deviation;
        double wl = std::abs(l - luminance(glm::dvec3(c))) / (s.phiLuminance * scale + 1e-10);
        w *= std::exp(-wz - wl) * wn;
      }
      colour += w * glm::dvec3(c);
      variance += w * w * c.w;
      weights += w;
    }
  return glm::vec4(glm::vec3(colour / weights), float(variance / (weights * weights)));
}

}  // namespace

std::vector<float> svgfDepthSlopes(const SvgfAtrousInput& input) {
  const Grid g{input};
  std::vector<float> slopes(size_t(input.width) * input.height, 0.0f);
  for (int y = 0; y < int(input.height); ++y)
    for (int x = 0; x < int(input.width); ++x)
      if (g.surface(x, y)) slopes[g.index(x, y)] = float(depthSlope(g, x, y));
  return slopes;
}

std::vector<glm::vec4> svgfAtrousReference(const SvgfAtrousInput& input, uint32_t iteration,
                                           const SvgfSettings& settings) {
  const Grid g{input};
  std::vector<glm::vec4> out(input.colourVariance);
  const bool last = iteration + 1 == settings.iterations;
  for (int y = 0; y < int(input.height); ++y)
    for (int x = 0; x < int(input.width); ++x) {
      glm::vec4& o = out[g.index(x, y)];
      if (g.surface(x, y))
        o = filterPixel(g, x, y, iteration, settings);
      else if (last && o.w < 0.0f)  // gpu::SVGF_NO_SURFACE_VARIANCE
        o.w = 0.0f;
    }
  return out;
}

}  // namespace bounce
