#include "gi/evolve/restir/restir_gi.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "core/blue_noise.h"
#include "core/error.h"
#include "graph/resource_desc.h"
#include "rt/gpu_scene.h"

namespace bounce {

namespace {

template <typename T>
vk::Buffer upload(vk::Context& context, std::span<const T> items, const std::string& name) {
  return vk::uploadBuffer(context, std::as_bytes(items), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
}

// The blue noise of gi-prepare-diffuse-rays' directions, generated once per process (~50 ms).
const std::vector<uint32_t>& directionBlueNoise() {
  static const std::vector<uint32_t> noise =
      generateBlueNoise2D(gpu::RESTIR_GI_BLUE_NOISE_SIDE, /*seed=*/0x9E3779B97F4A7C15ull);
  return noise;
}

}  // namespace

void validate(const RestirGiSettings& s) {
  if (s.divisor == 0 || s.divisor > 16)
    fail("ReSTIR GI: resolution divisor {} must be 1 to 16", s.divisor);
  if (!(s.settleHistoryScale > 0.0f && s.settleHistoryScale <= 1.0f))
    fail("ReSTIR GI: settle history scale {} must be in (0, 1]", s.settleHistoryScale);
  // gi_restir_spatial.comp keeps the merged neighbours for its 1/Z normalisation.
  for (uint32_t n : s.spatialSamples)
    if (n > gpu::RESTIR_GI_MAX_SPATIAL_SAMPLES)
      fail("ReSTIR GI: {} spatial samples per pass, at most {}", n,
           gpu::RESTIR_GI_MAX_SPATIAL_SAMPLES);
  if (s.temporalHistorySamples < 1 || s.temporalHistorySamples > 5)
    fail("ReSTIR GI: {} temporal history samples; expected 1 to 5", s.temporalHistorySamples);
  if (s.spatialDenoiseRadius > gpu::GI_SPATIAL_DENOISE_MAX_RADIUS)
    fail("ReSTIR GI: spatial denoise radius {}; at most {}", s.spatialDenoiseRadius,
         gpu::GI_SPATIAL_DENOISE_MAX_RADIUS);
  if (!(s.spatialMinRadius >= 0.5f))
    fail("ReSTIR GI: spatial minimum radius {} px must be at least 0.5", s.spatialMinRadius);
  if (s.historyBrightening != 0.0f && !(s.historyBrightening > 1.0f))
    fail("ReSTIR GI: history brightening {}: expected 0 (off) or a ratio above 1",
         s.historyBrightening);
  if (s.fireflyRatio != 0.0f && !(s.fireflyRatio > 1.0f))
    fail("ReSTIR GI: firefly ratio {}: expected 0 (off) or a ratio above 1", s.fireflyRatio);
  if (s.maxSampleAge > 100000)
    fail("ReSTIR GI: maximum sample age {}: expected 0 (no limit) to 100000 frames",
         s.maxSampleAge);
  // The history length travels in a half float (exact integers up to 2048), doubled where the
  // spatial occlusion validity is low.
  if (!(s.denoiseMaxHistory >= 1.0f && s.denoiseMaxHistory <= 1024.0f))
    fail("ReSTIR GI: denoise history {} frames: expected 1 to 1024", s.denoiseMaxHistory);
  if (!(s.spatialWideMaxM >= 0.0f) || !std::isfinite(s.spatialWideMaxM))
    fail("ReSTIR GI: spatial wide-pass M limit {}: expected 0 (every reservoir) or more",
         s.spatialWideMaxM);
  if (!(s.temporalMaxM >= 1.0f && s.temporalMaxM <= 1000.0f))
    fail("ReSTIR GI: temporal max M {}: expected 1 to 1000", s.temporalMaxM);
  if (!(s.movingTemporalMaxM >= 1.0f && s.movingTemporalMaxM <= 1000.0f))
    fail("ReSTIR GI: moving temporal max M {}: expected 1 to 1000", s.movingTemporalMaxM);
  if (!(s.movingPixels > 0.0f && s.movingPixels <= 1000.0f))
    fail("ReSTIR GI: moving pixels {}: expected more than 0, at most 1000", s.movingPixels);
  if (s.materialTextureSide > 2048)
    fail("ReSTIR GI: material texture side {}: expected 0 (full resolution) to 2048 texels",
         s.materialTextureSide);
}

RestirGi::RestirGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                   const RestirGiSettings& settings, const ClipmapCacheSettings& cache,
                   VkExtent2D resolution)
    : settings_(settings),
      lights_(context, gpuScene, scene),
      candidates_(context, gpuScene, secondVertexConstant(settings.secondVertex)),
      temporal_(context, gpuScene),
      spatial_(context, gpuScene, settings),
      resolve_(context, gpuScene, settings) {
  if (settings_.secondVertex == RestirGiSecondVertex::Cache)
    cache_ = std::make_unique<ClipmapCache>(context, gpuScene, lights_, cache);
  validate(settings_);
  if (auto kind = libraryDenoiser(settings_.denoiser))
    libraryDenoiser_ = std::make_unique<LibraryDenoiser>(
        context, gpuScene, *kind,
        LibraryDenoiserSettings{settings_.svgf, settings_.reblur, settings_.hybrid});
  if (evolveDenoise()) temporalDenoise_.emplace(context, gpuScene);
  if (evolveDenoise() && settings_.spatialDenoise) spatialDenoise_.emplace(context, gpuScene);
  settleFramesLeft_ = settings_.settleFrames;  // the first frames: the cache starts empty
  giResolution_ = graph::ImageSize::dividedRes(settings_.divisor).resolve(resolution);
  blueNoise_ = upload(context, std::span<const uint32_t>(directionBlueNoise()), "gi.blue-noise");
  const gpu::RestirGiConstants c = makeConstants();
  constants_ = upload(context, std::span<const gpu::RestirGiConstants>(&c, 1), "gi.constants");
}

gpu::RestirGiConstants restirGiConstants(const RestirGiSettings& s, VkExtent2D giResolution,
                                         VkDeviceAddress lights, VkDeviceAddress cache,
                                         VkDeviceAddress blueNoise, bool evolveDenoise) {
  gpu::RestirGiConstants c{};
  c.lights = lights;
  c.giResolution = {giResolution.width, giResolution.height};
  c.divisor = s.divisor;
  c.secondVertex = secondVertexConstant(s.secondVertex);
  c.flags =
      (s.temporalReuse ? gpu::RESTIR_GI_FLAG_TEMPORAL : 0u) |
      (evolveDenoise ? gpu::RESTIR_GI_FLAG_DENOISE : 0u) |
      (s.resolveSamples > 1 ? gpu::RESTIR_GI_FLAG_RESOLVE_REUSE : 0u) |
      (s.spatialReuse ? gpu::RESTIR_GI_FLAG_SPATIAL : 0u) |
      (s.spatialReuse && s.spatialValidation ? gpu::RESTIR_GI_FLAG_SPATIAL_VALIDATION : 0u) |
      (s.spatialReuse && s.spatialValidation && s.patchReservoir ? gpu::RESTIR_GI_FLAG_PATCH : 0u);
  c.maxPathBounces = s.maxBounces;
  c.temporalMaxM = s.temporalMaxM;
  c.movingTemporalMaxM = s.movingTemporalMaxM;
  c.movingPixels = s.movingPixels;
  c.maxSampleAge = s.maxSampleAge;
  c.spatialWideMaxM = s.spatialWideMaxM;
  c.planeTolerance = s.planeTolerance;
  c.normalTolerance = s.normalTolerance;
  c.maxJacobian = s.maxJacobian;
  c.denoiseMaxHistory = s.denoiseMaxHistory;
  c.denoiseClipSigma = s.denoiseClipSigma;
  c.resolveRadius = s.resolveRadius;
  c.resolveSamples = s.resolveSamples;
  c.cache = cache;
  for (int i = 0; i < 2; ++i) {
    c.spatialSamples[i] = s.spatialSamples[i];
    c.spatialRadius[i] = s.spatialRadius[i];
  }
  c.spatialMinRadius = s.spatialMinRadius;
  c.validityBlend = s.validityBlend;
  c.validationPeriod = s.validationPeriod;
  c.validationDistance = s.validationDistance;
  c.validationRadiance = s.validationRadiance;
  c.temporalHistorySamples = s.temporalHistorySamples;
  c.spatialDenoiseRadius = s.spatialDenoiseRadius;
  c.historyBrightening = s.historyBrightening;
  c.fireflyRatio = s.fireflyRatio;
  c.materialTextureSide = s.materialTextureSide;
  c.blueNoise = s.blueNoise ? blueNoise : 0;
  c.flags |= s.validationPeriod > 0 ? gpu::RESTIR_GI_FLAG_VALIDATION : 0u;
  c.flags |= s.occluderVisibility ? gpu::RESTIR_GI_FLAG_OCCLUDER_VISIBILITY : 0u;
  c.flags |= s.producerNormalisation ? gpu::RESTIR_GI_FLAG_PRODUCER_NORMALISATION : 0u;
  c.flags |= s.canonicalResolve ? gpu::RESTIR_GI_FLAG_CANONICAL_RESOLVE : 0u;
  c.flags |= s.temporalProducerNormalisation ? gpu::RESTIR_GI_FLAG_TEMPORAL_PRODUCERS : 0u;
  return c;
}

gpu::RestirGiConstants RestirGi::makeConstants() const {
  return restirGiConstants(settings_, giResolution_, lights_.address(),
                           cache_ ? cache_->constantsAddress() : 0, blueNoise_.address(),
                           evolveDenoise());
}

bool RestirGi::evolveDenoise() const {
  return settings_.denoiser == GiDenoiser::Evolve && settings_.temporalDenoise;
}

void RestirGi::afterFrame() {
  if (cache_) cache_->afterFrame();
  // One-shot and countdown state advances here, after the frame ran, never while declaring.
  lightCutPending_ = false;
  if (settleFramesLeft_ > 0) --settleFramesLeft_;
}

std::vector<GiStatistic> RestirGi::statistics() const {
  return cache_ ? cache_->statistics() : std::vector<GiStatistic>{};
}

void RestirGi::resetHistory() {
  if (cache_) cache_->resetHistory();
  settleFramesLeft_ = settings_.settleFrames;
}

void RestirGi::lightingCut() {
  if (cache_) cache_->beginFullRefresh();
  lightCutPending_ = true;
  settleFramesLeft_ = settings_.settleFrames;
}

RestirFrame RestirGi::beginFrame(const GiInputs& inputs) {
  RestirFrame f;
  f.in = inputs;
  f.giSize = graph::ImageSize::dividedRes(settings_.divisor);
  f.giResolution = giResolution_;
  f.constants = constants_.address();
  f.historyScale = settleFramesLeft_ > 0 ? settings_.settleHistoryScale : 1.0f;
  f.lightCutPending = lightCutPending_;
  return f;
}

// The chain, top to bottom (restir_gi.h). GI-resolution images follow the render resolution.
DiffuseGiOutput RestirGi::declare(graph::FrameGraph& graph, const GiInputs& in) {
  graph::ImageHandle output = createOutput(graph);
  if (cache_) cache_->declareUpdate(graph, in);
  RestirFrame f = beginFrame(in);
  f.rayLists = declareRayLists(graph);
  const ReservoirHistory history = createReservoirHistory(graph, f.giSize);
  // Written by gi-trace-spatial-validation-rays, read (previous) by the next frame's
  // gi-restir-temporal.
  std::optional<graph::HistoryImage> occlusionValidity;
  if (settings_.spatialReuse && settings_.spatialValidation)
    occlusionValidity =
        graph.createHistoryImage("gi.spatial-occlusion-validity", {VK_FORMAT_R16_SFLOAT, f.giSize});
  Candidates candidates = candidates_.declare(graph, f, history, cache_.get());
  Reservoirs temporal = temporal_.declare(graph, f, candidates, history, occlusionValidity);
  Reservoirs reservoirs = spatial_.declare(graph, f, temporal, occlusionValidity);
  const bool denoised = evolveDenoise() || libraryDenoiser_;
  graph::ImageHandle target =
      denoised ? graph.createImage("gi.resolved", {VK_FORMAT_R16G16B16A16_SFLOAT}) : output;
  ResolvedGi resolved = resolve_.declare(graph, f, reservoirs, target);
  if (libraryDenoiser_) {
    // gi.resolved is radiance per unit albedo already (gi/diffuse_gi.h): no demodulation.
    const GBuffer& g = in.gbuffer;
    SvgfInputs s{resolved.diffuse, g.depth.current, g.normals, g.velocity};
    s.octahedralNormals = true;
    s.dropHistory = f.lightCutPending;
    libraryDenoiser_->declare(graph, in.frame.resolution, s, output);
  } else if (evolveDenoise()) {
    declareDenoise(graph, f, candidates, resolved, occlusionValidity, output);
  }
  return {output};
}

// gi-temporal-denoise, then on the desktop preset gi-spatial-denoise; both end in `output`.
void RestirGi::declareDenoise(graph::FrameGraph& graph, const RestirFrame& f,
                              const Candidates& candidates, const ResolvedGi& resolved,
                              const std::optional<graph::HistoryImage>& occlusionValidity,
                              graph::ImageHandle output) {
  const bool spatial = settings_.spatialDenoise;
  graph::ImageHandle temporalOut =
      spatial ? graph.createImage("gi.temporal-denoised", {VK_FORMAT_R16G16B16A16_SFLOAT}) : output;
  GiTemporalDenoiseInputs t;
  t.noisy = resolved.diffuse;
  t.validity = candidates.validity;
  if (occlusionValidity) t.occlusionValidity = occlusionValidity->current;
  t.placeholderR16f = candidates.neeVisibility;
  t.constants = f.passConstants(false);
  t.dropHistory = f.lightCutPending;
  temporalDenoise_->declare(graph, f.in.frame, f.in.gbuffer, t, temporalOut);
  if (!spatial) return;
  spatialDenoise_->declare(graph, f.in.frame, f.in.gbuffer,
                           {temporalOut, resolved.occlusion, f.passConstants(false)}, output);
}

}  // namespace bounce
