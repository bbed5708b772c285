// Image-error metrics for comparing a render against a reference (DESIGN.md §6): MSE, relMSE,
// PSNR, and the perceptual FLIP (tools/flip.h). Every function takes (test, reference), reads
// the RGB channels only (alpha is ignored) and requires equal sizes.
#pragma once
#include "tools/flip.h"
#include "tools/image_io.h"

namespace bounce {

// relMSE's epsilon: keeps black reference pixels from dividing by zero while barely changing
// the value where the reference is brighter than ~0.1. It is the value commonly used to report
// Monte-Carlo rendering error (e.g. Rousselle et al., "Robust Denoising using Feature and Color
// Information", 2013).
constexpr double kRelMseEpsilon = 0.01;

// Mean over pixels and RGB channels of (test - reference)^2, on the linear values.
double meanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// Mean over pixels and RGB channels of (test - reference)^2 / (reference^2 + kRelMseEpsilon),
// on the linear values: scale-independent, so dark and bright regions count alike.
double relativeMeanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// PSNR in dB of display-referred images: both sRGB-encoded (clamped to [0,1]), peak 1. This is
// the PSNR image tools report for PNGs. +infinity for identical images.
double psnrLdr(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// PSNR in dB of scene-referred images: on the linear values, with the peak taken as the
// reference's largest RGB value (there is no fixed white in HDR). +infinity when identical.
double psnrHdr(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// Pixels with a NaN or infinite RGB value (such images cannot be compared meaningfully).
size_t countNonFinitePixels(const ImageRGBA32F& image);

}  // namespace bounce
