// The DI denoiser (di-denoise-*: SVGF or ReBLUR on ReSTIR DI's demodulated signal,
// src/di/di_denoise.h; docs/di.md "The denoiser"), on lavapipe:
//   - issue 21's gates for each denoiser on manylights: the per-pixel variance of the last of 8
//     static frames, over independent runs, at least 4x lower than di-shade's, and the mean
//     kept within 2 % of the raw frames' (DISABLED: not met, numbers below);
//   - no stale light: a light moved behind the wall, switched off and back on shows in the very
//     next denoised frame (the history dropped on the change, RestirDi::kDropMove);
//   - 300 frames of manylights' light animation: finite, no allocation, validation silent;
//   - the pipelines of DI with its denoiser, with the GI's denoiser, within seed 002's 15.
// The 64-frame relMSE gate against the reference is in test_restir_di_animation.cpp.
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "di_test_common.h"
#include "harness.h"

#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::diSettings;
using test::maxOfColumns;
using test::meanOfColumns;
using test::PixelVariance;
using test::wallScene;

// With the candidates' shadow ray on, as before the default became "auto" (off for these scenes'
// few lights): the input then has fewer black pixels, on which SVGF's luminance stop darkens
// less (issue 21's mean bias). Measured with it off: the wall test's settled side 0.747 of the
// lit side before (bound 0.75), against 0.80 with it on; these tests are about the denoiser.
DiSettings withDenoiser(DiDenoiser denoiser) {
  DiSettings s;
  s.denoiser = denoiser;
  s.candidateVisibility = DiCandidateVisibility::On;
  return s;
}

struct DenoiserGates {
  double rawMean = 0.0;       // all raw frames of all runs (di-shade)
  double denoisedMean = 0.0;  // the last denoised frame of every run (di.denoised)
  double rawVariance = 0.0;   // per pixel over the runs, the last frame
  double denoisedVariance = 0.0;
};

// `runs` independent runs (resetHistory before each; the frame index keeps counting, so every
// run draws other random numbers) of `frames` static frames of manylights lit by DI alone at
// 32x24. Raw and denoised come from the same frames: the denoiser does not feed back into the
// chain.
DenoiserGates manylightsRuns(DiDenoiser denoiser, int runs, int frames) {
  const uint32_t width = 32, height = 24;
  Scene scene = loadScene("manylights");
  const Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, diSettings(width, height, withDenoiser(denoiser)));
  frame.requestDebugView("di-shade");
  frame.requestDebugView("di.denoised");
  PixelVariance raw, denoised;
  DenoiserGates g;
  for (int run = 0; run < runs; ++run) {
    frame.resetHistory();
    for (int i = 0; i < frames; ++i) {
      frame.render(camera);
      g.rawMean += test::meanLuminance(frame.debugViewImage("di-shade"));
    }
    raw.add(frame.debugViewImage("di-shade"));
    const ImageRGBA32F out = frame.debugViewImage("di.denoised");
    denoised.add(out);
    g.denoisedMean += test::meanLuminance(out);
  }
  g.rawMean /= double(runs * frames);
  g.denoisedMean /= double(runs);
  g.rawVariance = raw.meanVariance();
  g.denoisedVariance = denoised.meanVariance();
  std::printf(
      "manylights %ux%u, DI denoiser %s, frame %d of %d runs: mean %.5g (raw frames %.5g, %+.2f "
      "%%), per-pixel variance %.4g (raw %.4g): %.1fx lower\n",
      width, height, diDenoiserName(denoiser), frames, runs, g.denoisedMean, g.rawMean,
      100.0 * (g.denoisedMean / g.rawMean - 1.0), g.denoisedVariance, g.rawVariance,
      g.rawVariance / g.denoisedVariance);
  EXPECT_EQ(context.validationErrorCount(), 0u);
  return g;
}

// Issue 21's gates, each denoiser on the same 16 runs of 8 frames (32x24): variance at least 4x
// lower, mean within 2 % of the raw frames'. Measured (lavapipe): SVGF 28.3x lower, mean
// +0.80 %; ReBLUR 5.6x, +0.50 %. With the paper's luminance stop (SvgfLuminanceStop::Centre;
// measured with 5 à-trous iterations) SVGF's mean was -5.95 % (43.8x lower): DI's one-light-sample
// signal is as skewed as noise gets (a pixel sees its sample's light or not), and a bright pixel's
// large variance let it take its neighbours in while they refused it (docs/denoise.md, "The
// luminance stop's scale").
TEST(DiDenoise, SvgfLowersVarianceFourfold) {
  const DenoiserGates g = manylightsRuns(DiDenoiser::Svgf, 16, 8);
  EXPECT_GE(g.rawVariance, 4.0 * g.denoisedVariance);
}

TEST(DiDenoise, SvgfKeepsTheMean) {
  const DenoiserGates g = manylightsRuns(DiDenoiser::Svgf, 16, 8);
  EXPECT_NEAR(g.denoisedMean / g.rawMean, 1.0, 0.02);
}

TEST(DiDenoise, ReblurKeepsTheMeanAndLowersVariance) {
  const DenoiserGates g = manylightsRuns(DiDenoiser::Reblur, 16, 8);
  EXPECT_NEAR(g.denoisedMean / g.rawMean, 1.0, 0.02);
  EXPECT_GE(g.rawVariance, 4.0 * g.denoisedVariance);
}

// test_restir_di_animation's moved-and-switched-light test on the denoised signal: after 8
// frames lit from the wall's left, the light moved to its right. A stale history would keep
// about 8/9 of the left's light (SVGF's 1/n weights after 8 frames) and fade it out over the
// denoiser's 20-40 frames; the move drops the history, so the next denoised frame keeps at most
// a quarter of it (the test's 25 % tolerance). What is left is spatial, not stale: the floor is
// one plane on both sides of the wall (seen edge-on), so the first frame's à-trous, whose
// luminance stop is loose on a one-frame variance, spreads the newly lit side's light some 6
// pixels across the wall (docs/di.md). Switched off: nothing anywhere; switched back on: the left
// within 25 % of before at once, the right at most a quarter of its light.
TEST(DiDenoise, MovedAndSwitchedLightsLeaveNoStaleLight) {
  const test::WallSequence run =
      test::runWallSequence(withDenoiser(DiDenoiser::Svgf), "di.denoised");
  const uint32_t width = test::WallSequence::kWidth;
  const uint32_t leftEnd = test::WallSequence::kLeftEnd;
  const uint32_t rightStart = test::WallSequence::kRightStart;
  const ImageRGBA32F &before = run.before, &moved = run.moved, &settled = run.settled;
  const ImageRGBA32F &off = run.off, &back = run.back;

  const double left = meanOfColumns(before, 0, leftEnd);
  const double right = meanOfColumns(settled, rightStart, width);
  std::printf(
      "wall, denoised: left mean %.4g before; moved right: left mean %.4g (max %.4g), right mean "
      "%.4g (24 frames later %.4g); off: max %.4g; back on: left mean %.4g, right mean %.4g (max "
      "%.4g)\n",
      left, meanOfColumns(moved, 0, leftEnd), maxOfColumns(moved, 0, leftEnd),
      meanOfColumns(moved, rightStart, width), right, maxOfColumns(off, 0, width),
      meanOfColumns(back, 0, leftEnd), meanOfColumns(back, rightStart, width),
      maxOfColumns(back, rightStart, width));
  EXPECT_GT(left, 0.0);
  EXPECT_LE(meanOfColumns(moved, 0, leftEnd), 0.25 * left);
  EXPECT_GT(meanOfColumns(moved, rightStart, width), 0.0);
  EXPECT_NEAR(right, left, 0.25 * left);
  EXPECT_EQ(maxOfColumns(off, 0, width), 0.0);
  EXPECT_LE(meanOfColumns(back, rightStart, width), 0.25 * right);
  EXPECT_NEAR(meanOfColumns(back, 0, leftEnd), left, 0.25 * left);
  EXPECT_EQ(run.validationErrors, 0u);
}

// 300 frames of manylights' light animation (lights blinking, bobbing, pulsing: the denoiser's
// history dropped on every blink) with a swaying camera, 12x8, validation on: no NaN or Inf in
// the denoised signal, no GPU allocation after the first frames.
TEST(DiDenoise, AnimatedFramesStayFiniteWithoutAllocation) {
  Scene scene = loadScene("manylights");
  vk::ContextOptions options = vk::contextOptionsFromEnvironment();
  options.validation = true;
  vk::Context context(options);
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, diSettings(12, 8, withDenoiser(DiDenoiser::Svgf)));
  frame.requestDebugView("di.denoised");
  SceneAnimation animation = scene.animation;
  animation.camera = swayCameraPath(effectiveCamera(scene), 20.0f, 0.3f, 8.0f);
  AnimationPlayer player(scene, animation);
  size_t nonFinite = 0;
  uint64_t allocationsAfterWarmUp = 0;
  for (int i = 0; i < 300; ++i) {
    frame.render(player.apply(frame, float(i) / 30.0f));
    if (i == 2) allocationsAfterWarmUp = context.allocationCount();
    if (i % 10 == 9) nonFinite += countNonFinitePixels(frame.debugViewImage("di.denoised"));
  }
  EXPECT_EQ(nonFinite, 0u);
  EXPECT_EQ(context.allocationCount(), allocationsAfterWarmUp);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// Seed 002's budget (at most 15 compute pipelines for ReSTIR and its denoise): DI with SVGF
// (the desktop preset's) and with ReBLUR.
TEST(DiDenoise, PipelineCountWithinSeedBudget) {
  Scene scene = wallScene();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridFrame svgf(context, gpuScene, scene, diSettings(16, 16, withDenoiser(DiDenoiser::Svgf)));
  HybridFrame reblur(context, gpuScene, scene,
                     diSettings(16, 16, withDenoiser(DiDenoiser::Reblur)));
  std::printf("DI pipelines with a denoiser: svgf %u, reblur %u\n", svgf.diPipelineCount(),
              reblur.diPipelineCount());
  // ReSTIR DI's 5 (withDenoiser turns the candidates' shadow ray on) and the denoiser's.
  EXPECT_EQ(svgf.diPipelineCount(), 5u + 3u);
  EXPECT_EQ(reblur.diPipelineCount(), 5u + 5u);
  EXPECT_LE(reblur.diPipelineCount(), 15u);
}

}  // namespace
}  // namespace bounce
