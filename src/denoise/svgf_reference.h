// A CPU reference of one SVGF à-trous iteration (svgf-atrous-N, shaders/denoise/svgf_atrous.comp;
// Schied et al. 2017 §4.2), in double precision, written from the paper rather than from the
// shader: what tests compare the GPU pass with (issue 21, seed 002's "CPU reference of the
// à-trous step").
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "denoise/svgf.h"

namespace bounce {

// An image of svgf-atrous's inputs, row-major, width x height.
struct SvgfAtrousInput {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> colourVariance;  // rgb colour, a luminance variance (-1: no surface)
  std::vector<glm::vec4> surface;         // xyz unit normal, w view depth (<= 0: no surface)
};

// One iteration with tap spacing 2^iteration and the settings' edge stops; returns rgb colour
// and a variance per pixel. Pixels without a surface keep their input (their variance
// SVGF_NO_SURFACE_VARIANCE, the last iteration's 0).
std::vector<glm::vec4> svgfAtrousReference(const SvgfAtrousInput& input, uint32_t iteration,
                                           const SvgfSettings& settings);

// Per pixel, the view depth's change per pixel that svgf-temporal writes to svgf.slope and the
// iterations read (of the two one-sided differences along each axis the smaller; 0 without a
// surface): what a test uploads beside the à-trous step's input.
std::vector<float> svgfDepthSlopes(const SvgfAtrousInput& input);

}  // namespace bounce
