// The denoisers alone: Bounce's library denoisers of a diffuse signal (docs/denoise.md), with no
// renderer and no GI technique. Each frame the host gives the noisy signal and the surface it
// lies on (view depth, normal, motion, optionally an albedo) as float images in host memory;
// denoise() uploads them, runs one frame of the denoiser on Bounce's own Vulkan device (as
// Renderer::create(scene) picks it; BOUNCE_DEVICE=N, BOUNCE_VALIDATE=1), waits and returns the
// denoised signal. The denoisers are temporal: call it once per frame, in order, and
// resetHistory() at a camera cut.
//
//   bounce::Denoiser denoiser = bounce::Denoiser::create(bounce::DenoiserKind::Reblur, 640, 360);
//   bounce::DenoiserFrame frame = ...;  // noisy, depth, normal, motion of this frame
//   bounce::Image clean = denoiser.denoise(frame);
//
// The images (width x height each, rows top to bottom, as Image's rgba floats or one or two
// floats per pixel):
//   noisy   Image   rgb the signal (e.g. diffuse radiance per unit albedo), a ignored; stored
//                   as 16-bit floats on the GPU (keep it below 65504)
//   depth   floats  linear view depth, 1 per pixel; 0, negative or non-finite: no surface (the
//                   signal passes through there). Only depth ratios matter (any unit).
//   normal  Image   world-space unit normal in rgb, a ignored
//   motion  floats  2 per pixel: this frame's pixel position minus last frame's (x right,
//                   y down, in pixels; 0 for a still view)
//   albedo  Image   optional (empty: none): the signal is divided by it before filtering and
//                   multiplied back after, so the filter blurs lighting and not texture
// The result: rgb the denoised signal, a the denoiser's own (SVGF: remaining luminance
// variance; ReBLUR: history length in frames; hybrid: SVGF's weight in [0, 1]).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bounce/config.h"
#include "bounce/image.h"

namespace bounce::api {

enum class DenoiserKind {
  Svgf,    // spatiotemporal variance-guided filtering (Schied et al. 2017), Falcor's parameters
           // with NRD RELAX's 3x3 à-trous
  Reblur,  // ReBLUR-style: NRD REBLUR_DIFFUSE's passes and defaults
  Hybrid,  // SVGF or ReBLUR per pixel, from history length, motion and variance
};

// "svgf", "reblur", "hybrid" -> the kind; throws bounce::Error for another name.
DenoiserKind denoiserKindFromName(const std::string& name);

struct DenoiserFrame {
  Image noisy;
  std::vector<float> depth;  // width x height
  Image normal;
  std::vector<float> motion;  // 2 x width x height
  Image albedo;               // optional: width 0 for none
};

class Denoiser {
 public:
  // Creates the device and the denoiser's pipelines and images for width x height (each 1 to
  // 8192). Throws bounce::Error for a bad size or a device that cannot run Bounce.
  static Denoiser create(DenoiserKind kind, uint32_t width, uint32_t height);
  ~Denoiser();
  Denoiser(Denoiser&& other) noexcept;
  Denoiser& operator=(Denoiser&& other) noexcept;

  // One frame: the denoised signal. Throws bounce::Error naming the image whose size is not the
  // denoiser's.
  Image denoise(const DenoiserFrame& frame);
  // Forgets temporal history (a camera cut): the next frame starts afresh.
  void resetHistory();

  DenoiserKind kind() const;
  // The compute pipelines it compiled (issue 21's permutation budget): SVGF 3, ReBLUR 5,
  // hybrid 10.
  uint32_t pipelineCount() const;
  std::string deviceName() const;

 private:
  struct Impl;
  explicit Denoiser(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce::api
