// Error maps as pictures. Our colour map ("ember") is a ramp built in OKLab: lightness rises
// linearly from near-black to near-white while the hue turns from violet through red and
// orange to pale yellow, so that brighter always means a larger error, also in grey print and
// for colour-blind readers. Its chroma is reduced where a colour would leave the sRGB gamut, which
// keeps the lightness ramp exact.
#pragma once
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace bounce {

struct FlipResult;

// The colour map at t in [0,1] (clamped; NaN counts as 0), as sRGB-encoded values in [0,1].
glm::vec3 heatmapColor(float t);

// Writes a PNG of `errorMap` (width x height values in [0,1], rows top to bottom) through the
// colour map. Throws bounce::Error when the sizes disagree or the file cannot be written.
void writeHeatmap(const std::string& path, const std::vector<float>& errorMap, int width,
                  int height);
void writeHeatmap(const std::string& path, const FlipResult& flip);

}  // namespace bounce
