#include "gi/evolve/restir_gi.h"

#include <algorithm>
#include <optional>
#include <span>
#include <vector>

#include "core/blue_noise.h"
#include "core/error.h"
#include "rt/gpu_scene.h"

namespace bounce {

namespace {

using graph::Access;
using graph::ImageSize;
using graph::QueueKind;

constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
// The four images of a reservoir (shared/restir_gi_io.h).
constexpr const char* kReservoirParts[4] = {"sample", "radiance", "origin", "normals"};
constexpr VkFormat kReservoirFormats[4] = {kRgba32f, kRgba32f, kRgba32f, kRgba16f};

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

RestirGi::RestirGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                   const RestirGiSettings& settings, const ClipmapCacheSettings& cache,
                   VkExtent2D resolution)
    : settings_(settings),
      lights_(context, gpuScene, scene),
      prepare_(context, gpuScene, "gi/evolve/gi_prepare_diffuse_rays",
               gpu::GI_PREPARE_BINDING_COUNT),
      trace_(context, gpuScene, "gi/evolve/gi_trace_diffuse_rays", gpu::GI_TRACE_BINDING_COUNT),
      traceNee_(context, gpuScene, "gi/evolve/gi_trace_diffuse_nee_rays",
                gpu::GI_NEE_BINDING_COUNT),
      candidates_(context, gpuScene, "gi/evolve/gi_resolve_diffuse_rays",
                  gpu::GI_CANDIDATES_BINDING_COUNT),
      temporal_(context, gpuScene, "gi/evolve/gi_restir_temporal", gpu::GI_TEMPORAL_BINDING_COUNT),
      spatial0_(context, gpuScene, "gi/evolve/gi_restir_spatial", gpu::GI_SPATIAL_BINDING_COUNT),
      spatial1_(context, gpuScene, "gi/evolve/gi_restir_spatial", gpu::GI_SPATIAL_BINDING_COUNT),
      spatialValidation_(context, gpuScene, "gi/evolve/gi_trace_spatial_validation_rays",
                         gpu::GI_VALIDATION_BINDING_COUNT),
      patch_(context, gpuScene, "gi/evolve/gi_restir_patch_reservoir",
             gpu::GI_SPATIAL_BINDING_COUNT),
      resolveVisibility_(context, gpuScene, "gi/evolve/gi_trace_resolve_visibility",
                         gpu::GI_RESOLVE_VISIBILITY_BINDING_COUNT),
      resolve_(context, gpuScene, "gi/evolve/gi_restir_resolve", gpu::GI_RESOLVE_BINDING_COUNT),
      spatialDenoise_(context, gpuScene, "gi/evolve/gi_spatial_denoise",
                      gpu::GI_SPATIAL_DENOISE_BINDING_COUNT),
      denoise_(context, gpuScene, "gi/evolve/gi_temporal_denoise", gpu::GI_DENOISE_BINDING_COUNT) {
  const RestirGiSettings& s = settings_;
  if (s.secondVertex == RestirGiSecondVertex::Cache)
    cache_ = std::make_unique<ClipmapCache>(context, gpuScene, lights_, cache);
  if (s.divisor == 0 || s.divisor > 16)
    fail("ReSTIR GI: resolution divisor {} must be 1 to 16", s.divisor);
  if (!(s.settleHistoryScale > 0.0f && s.settleHistoryScale <= 1.0f))
    fail("ReSTIR GI: settle history scale {} must be in (0, 1]", s.settleHistoryScale);
  // gi_restir_spatial.comp keeps the merged neighbours for its 1/Z normalisation.
  for (uint32_t n : s.spatialSamples)
    if (n > gpu::RESTIR_GI_MAX_SPATIAL_SAMPLES)
      fail("ReSTIR GI: {} spatial samples per pass, at most {}", n, gpu::RESTIR_GI_MAX_SPATIAL_SAMPLES);
  settleFramesLeft_ = s.settleFrames;  // the first frames: the cache starts empty
  giResolution_ = {(resolution.width + s.divisor - 1) / s.divisor,
                   (resolution.height + s.divisor - 1) / s.divisor};

  blueNoise_ = upload(context, std::span<const uint32_t>(directionBlueNoise()), "gi.blue-noise");
  gpu::RestirGiConstants c{};
  c.lights = lights_.address();
  c.giResolution = {giResolution_.width, giResolution_.height};
  c.divisor = s.divisor;
  c.secondVertex = s.secondVertex == RestirGiSecondVertex::Path ? gpu::RESTIR_GI_SECOND_VERTEX_PATH
                   : s.secondVertex == RestirGiSecondVertex::Cache
                       ? gpu::RESTIR_GI_SECOND_VERTEX_CACHE
                       : gpu::RESTIR_GI_SECOND_VERTEX_NEE;
  c.flags =
      (s.temporalReuse ? gpu::RESTIR_GI_FLAG_TEMPORAL : 0u) |
      (s.temporalDenoise ? gpu::RESTIR_GI_FLAG_DENOISE : 0u) |
      (s.resolveSamples > 1 ? gpu::RESTIR_GI_FLAG_RESOLVE_REUSE : 0u) |
      (s.spatialReuse ? gpu::RESTIR_GI_FLAG_SPATIAL : 0u) |
      (s.spatialReuse && s.spatialValidation ? gpu::RESTIR_GI_FLAG_SPATIAL_VALIDATION : 0u) |
      (s.spatialReuse && s.spatialValidation && s.patchReservoir ? gpu::RESTIR_GI_FLAG_PATCH : 0u);
  c.maxPathBounces = s.maxBounces;
  c.temporalMaxM = s.temporalMaxM;
  c.maxSampleAge = s.maxSampleAge;
  c.planeTolerance = s.planeTolerance;
  c.normalTolerance = s.normalTolerance;
  c.maxJacobian = s.maxJacobian;
  c.denoiseMaxHistory = s.denoiseMaxHistory;
  c.denoiseClipSigma = s.denoiseClipSigma;
  c.resolveRadius = s.resolveRadius;
  c.resolveSamples = s.resolveSamples;
  c.cache = cache_ ? cache_->constantsAddress() : 0;
  for (int i = 0; i < 2; ++i) {
    c.spatialSamples[i] = s.spatialSamples[i];
    c.spatialRadius[i] = s.spatialRadius[i];
  }
  c.spatialMinRadius = std::max(s.spatialMinRadius, 0.5f);
  c.validityBlend = s.validityBlend;
  c.validationPeriod = s.validationPeriod;
  c.validationDistance = s.validationDistance;
  c.validationRadiance = s.validationRadiance;
  c.temporalHistorySamples = std::clamp(s.temporalHistorySamples, 1u, 5u);
  c.spatialDenoiseRadius = std::min(s.spatialDenoiseRadius, gpu::GI_SPATIAL_DENOISE_MAX_RADIUS);
  c.historyBrightening = s.historyBrightening > 1.0f ? s.historyBrightening : 0.0f;
  c.fireflyRatio = s.fireflyRatio > 1.0f ? s.fireflyRatio : 0.0f;
  c.materialTextureSide = s.materialTextureSide;
  c.blueNoise = s.blueNoise ? blueNoise_.address() : 0;
  c.flags |= s.validationPeriod > 0 ? gpu::RESTIR_GI_FLAG_VALIDATION : 0u;
  c.flags |= s.occluderVisibility ? gpu::RESTIR_GI_FLAG_OCCLUDER_VISIBILITY : 0u;
  c.flags |= s.producerNormalisation ? gpu::RESTIR_GI_FLAG_PRODUCER_NORMALISATION : 0u;
  constants_ = upload(context, std::span<const gpu::RestirGiConstants>(&c, 1), "gi.constants");
}

gpu::RestirGiPassConstants RestirGi::passConstants(const GiInputs& inputs, bool historyValid,
                                                   uint32_t variant) const {
  return {inputs.frame.constantsAddress, constants_.address(), historyValid ? 1u : 0u, variant,
          historyScale_, 0u};
}

// A reservoir-to-reservoir pass at GI resolution (gi-restir-spatial-0/1, patch): `estimate`
// first, so that it is the pass's debug view.
void RestirGi::declareReservoirPass(graph::FrameGraph& graph, const GiInputs& in,
                                    const char* name, RestirGiPass& pass, uint32_t variant,
                                    const ReservoirImages& input, const ReservoirImages& output,
                                    graph::ImageHandle estimate) {
  graph::PassBuilder b = graph.addPass(name, QueueKind::Compute);
  b.write(estimate, Access::StorageWrite)
      .read(in.frame.constants, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead);
  for (int i = 0; i < 4; ++i)
    b.read(input[i], Access::StorageRead).write(output[i], Access::StorageWrite);
  const VkExtent2D gi = giResolution_;
  b.record([=, this, &pass](VkCommandBuffer cmd, const graph::PassResources& r) {
    std::vector<ImageBinding> images = {{gpu::GI_SPATIAL_BINDING_NORMALS, r.image(in.gbuffer.normals)},
                                        {gpu::GI_SPATIAL_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
                                        {gpu::GI_SPATIAL_BINDING_ESTIMATE, r.image(estimate)}};
    for (uint32_t i = 0; i < 4; ++i) {
      images.push_back({gpu::GI_SPATIAL_BINDING_INPUT + i, r.image(input[i])});
      images.push_back({gpu::GI_SPATIAL_BINDING_OUTPUT + i, r.image(output[i])});
    }
    pass.record(cmd, images, passConstants(in, false, variant), gi);
  });
}

// gi-restir-spatial-0, -1, gi-trace-spatial-validation-rays, gi-restir-patch-reservoir, as
// enabled; returns the reservoir that gi-restir-resolve reads.
RestirGi::ReservoirImages RestirGi::declareSpatialChain(
    graph::FrameGraph& graph, const GiInputs& in, const ReservoirImages& temporal,
    const std::optional<graph::HistoryImage>& occlusionValidity) {
  if (!settings_.spatialReuse) return temporal;
  const ImageSize giSize = ImageSize::dividedRes(settings_.divisor);
  auto reservoirImages = [&](const std::string& prefix) {
    ReservoirImages images;
    for (int i = 0; i < 4; ++i)
      images[i] = graph.createImage(prefix + kReservoirParts[i], {kReservoirFormats[i], giSize});
    return images;
  };
  ReservoirImages spatial[2] = {reservoirImages("gi.spatial-0."), reservoirImages("gi.spatial-1.")};
  const char* names[2] = {"gi-restir-spatial-0", "gi-restir-spatial-1"};
  RestirGiPass* passes[2] = {&spatial0_, &spatial1_};
  for (uint32_t v = 0; v < 2; ++v) {
    graph::ImageHandle estimate = graph.createImage(
        std::string("gi.spatial-") + char('0' + v) + "-estimate", {kRgba16f, giSize});
    declareReservoirPass(graph, in, names[v], *passes[v], v, v == 0 ? temporal : spatial[0],
                         spatial[v], estimate);
  }
  if (!settings_.spatialValidation) return spatial[1];

  ReservoirImages validated = spatial[1];
  validated[0] = graph.createImage("gi.validated.sample", {kRgba32f, giSize});
  graph::ImageHandle estimate = graph.createImage("gi.validated-estimate", {kRgba16f, giSize});
  const graph::HistoryImage validity = *occlusionValidity;
  graph::PassBuilder b = graph.addPass("gi-trace-spatial-validation-rays", QueueKind::Compute);
  b.write(estimate, Access::StorageWrite)
      .read(in.frame.constants, Access::StorageRead)
      .read(in.frame.instances, Access::StorageRead)
      .read(in.frame.tlas, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(in.gbuffer.velocity, Access::StorageRead)
      .read(temporal[0], Access::StorageRead)
      .read(validity.previous, Access::StorageRead)
      .write(validity.current, Access::StorageWrite)
      .write(validated[0], Access::StorageWrite);
  for (int i = 0; i < 4; ++i) b.read(spatial[1][i], Access::StorageRead);
  const VkExtent2D gi = giResolution_;
  ReservoirImages input = spatial[1];
  graph::ImageHandle temporalSample = temporal[0];
  b.record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
    std::vector<ImageBinding> images = {
        {gpu::GI_VALIDATION_BINDING_TEMPORAL_SAMPLE, r.image(temporalSample)},
        {gpu::GI_VALIDATION_BINDING_NORMALS, r.image(in.gbuffer.normals)},
        {gpu::GI_VALIDATION_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
        {gpu::GI_VALIDATION_BINDING_VELOCITY, r.image(in.gbuffer.velocity)},
        {gpu::GI_VALIDATION_BINDING_VALIDITY_PREVIOUS, r.image(validity.previous)},
        {gpu::GI_VALIDATION_BINDING_VALIDITY_CURRENT, r.image(validity.current)},
        {gpu::GI_VALIDATION_BINDING_SAMPLE_OUT, r.image(validated[0])},
        {gpu::GI_VALIDATION_BINDING_ESTIMATE, r.image(estimate)}};
    for (uint32_t i = 0; i < 4; ++i)
      images.push_back({gpu::GI_VALIDATION_BINDING_INPUT + i, r.image(input[i])});
    spatialValidation_.record(cmd, images, passConstants(in, r.historyValid(validity)), gi);
  });
  if (!settings_.patchReservoir) return validated;
  ReservoirImages patched = reservoirImages("gi.patched.");
  declareReservoirPass(graph, in, "gi-restir-patch-reservoir", patch_, 0, validated, patched,
                       graph.createImage("gi.patched-estimate", {kRgba16f, giSize}));
  return patched;
}

// The chain, top to bottom (restir_gi.h). GI-resolution images follow the render resolution.
void RestirGi::afterFrame() {
  if (cache_) cache_->afterFrame();
  lightCutPending_ = false;
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

DiffuseGiOutput RestirGi::declare(graph::FrameGraph& graph, const GiInputs& in) {
  graph::ImageHandle output = createOutput(graph);
  if (cache_) cache_->declareUpdate(graph, in);
  historyScale_ = settleFramesLeft_ > 0 ? settings_.settleHistoryScale : 1.0f;
  if (settleFramesLeft_ > 0) --settleFramesLeft_;
  const ImageSize giSize = ImageSize::dividedRes(settings_.divisor);
  const VkExtent2D gi = giResolution_;
  const VkExtent2D full = in.frame.resolution;
  graph::ImageHandle rays = graph.createImage("gi.rays", {kRgba32f, giSize});
  graph::ImageHandle hit = graph.createImage("gi.hit", {kRgba32f, giSize});
  graph::ImageHandle hitNormal = graph.createImage("gi.hit-normal", {kRgba16f, giSize});
  graph::ImageHandle hitRadiance = graph.createImage("gi.hit-radiance", {kRgba32f, giSize});
  graph::ImageHandle neeRay = graph.createImage("gi.nee-ray", {kRgba32f, giSize});
  graph::ImageHandle neeRadiance = graph.createImage("gi.nee-radiance", {kRgba32f, giSize});
  graph::ImageHandle neeVisibility =
      graph.createImage("gi.nee-visibility", {VK_FORMAT_R16_SFLOAT, giSize});
  const char* const* kParts = kReservoirParts;
  const VkFormat* kPartFormats = kReservoirFormats;
  graph::ImageHandle candidate[4];
  graph::HistoryImage reservoir[4];
  for (int i = 0; i < 4; ++i) {
    candidate[i] =
        graph.createImage(std::string("gi.candidate.") + kParts[i], {kPartFormats[i], giSize});
    reservoir[i] = graph.createHistoryImage(std::string("gi.reservoir.") + kParts[i],
                                            {kPartFormats[i], giSize});
  }
  graph::ImageHandle candidateEstimate =
      graph.createImage("gi.candidate-estimate", {kRgba16f, giSize});
  graph::ImageHandle reservoirValidity =
      graph.createImage("gi.reservoir-validity", {kRgba16f, giSize});
  // Spatial occlusion validity: written by gi-trace-spatial-validation-rays, read (previous)
  // by the next frame's gi-restir-temporal.
  const bool spatialValidation = settings_.spatialReuse && settings_.spatialValidation;
  std::optional<graph::HistoryImage> occlusionValidity;
  if (spatialValidation)
    occlusionValidity =
        graph.createHistoryImage("gi.spatial-occlusion-validity", {VK_FORMAT_R16_SFLOAT, giSize});
  graph::ImageHandle reservoirEstimate =
      graph.createImage("gi.reservoir-estimate", {kRgba16f, giSize});
  // gi-restir-temporal's running mean of each neighbourhood's candidates and whether they were
  // brighter than it last frame (historyBrightening).
  graph::HistoryImage candidateMean =
      graph.createHistoryImage("gi.candidate-mean", {VK_FORMAT_R32G32_SFLOAT, giSize});
  const bool denoise = settings_.temporalDenoise;
  graph::ImageHandle resolved = denoise ? graph.createImage("gi.resolved", {kRgba16f}) : output;

  graph.addPass("gi-prepare-diffuse-rays", QueueKind::Compute)
      .write(rays, Access::StorageWrite)
      .read(in.frame.constants, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(in.gbuffer.flags, Access::StorageRead)
      .read(in.gbuffer.velocity, Access::StorageRead)
      .read(reservoir[0].previous, Access::StorageRead)
      .read(reservoir[2].previous, Access::StorageRead)
      .read(reservoir[3].previous, Access::StorageRead)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        bool valid = !lightCutPending_;
        for (int i = 0; i < 4; ++i) valid = valid && r.historyValid(reservoir[i]);
        prepare_.record(cmd,
                        {{gpu::GI_PREPARE_BINDING_NORMALS, r.image(in.gbuffer.normals)},
                         {gpu::GI_PREPARE_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
                         {gpu::GI_PREPARE_BINDING_FLAGS, r.image(in.gbuffer.flags)},
                         {gpu::GI_PREPARE_BINDING_RAYS, r.image(rays)},
                         {gpu::GI_PREPARE_BINDING_PREVIOUS_SAMPLE, r.image(reservoir[0].previous)},
                         {gpu::GI_PREPARE_BINDING_PREVIOUS_ORIGIN, r.image(reservoir[2].previous)},
                         {gpu::GI_PREPARE_BINDING_PREVIOUS_NORMALS, r.image(reservoir[3].previous)},
                         {gpu::GI_PREPARE_BINDING_VELOCITY, r.image(in.gbuffer.velocity)}},
                        passConstants(in, valid), gi);
      });
  graph::PassBuilder tracePass = graph.addPass("gi-trace-diffuse-rays", QueueKind::Compute);
  if (cache_) cache_->declareLookup(tracePass);
  tracePass.read(in.frame.constants, Access::StorageRead)
      .read(in.frame.instances, Access::StorageRead)
      .read(in.frame.tlas, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(rays, Access::StorageRead)
      .write(hit, Access::StorageWrite)
      .write(hitNormal, Access::StorageWrite)
      .write(hitRadiance, Access::StorageWrite)
      .write(neeRay, Access::StorageWrite)
      .write(neeRadiance, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        trace_.record(cmd,
                      {{gpu::GI_TRACE_BINDING_NORMALS, r.image(in.gbuffer.normals)},
                       {gpu::GI_TRACE_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
                       {gpu::GI_TRACE_BINDING_RAYS, r.image(rays)},
                       {gpu::GI_TRACE_BINDING_HIT, r.image(hit)},
                       {gpu::GI_TRACE_BINDING_HIT_NORMAL, r.image(hitNormal)},
                       {gpu::GI_TRACE_BINDING_HIT_RADIANCE, r.image(hitRadiance)},
                       {gpu::GI_TRACE_BINDING_NEE_RAY, r.image(neeRay)},
                       {gpu::GI_TRACE_BINDING_NEE_RADIANCE, r.image(neeRadiance)}},
                      passConstants(in, false), gi);
      });
  if (cache_) cache_->declareStatisticsReadback(graph);
  graph.addPass("gi-trace-diffuse-nee-rays", QueueKind::Compute)
      .read(in.frame.constants, Access::StorageRead)
      .read(in.frame.instances, Access::StorageRead)
      .read(in.frame.tlas, Access::StorageRead)
      .read(hit, Access::StorageRead)
      .read(hitNormal, Access::StorageRead)
      .read(neeRay, Access::StorageRead)
      .write(neeVisibility, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        traceNee_.record(cmd,
                         {{gpu::GI_NEE_BINDING_HIT, r.image(hit)},
                          {gpu::GI_NEE_BINDING_HIT_NORMAL, r.image(hitNormal)},
                          {gpu::GI_NEE_BINDING_NEE_RAY, r.image(neeRay)},
                          {gpu::GI_NEE_BINDING_VISIBILITY, r.image(neeVisibility)}},
                         passConstants(in, false), gi);
      });
  graph.addPass("gi-resolve-diffuse-rays", QueueKind::Compute)
      .read(in.frame.constants, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(rays, Access::StorageRead)
      .read(hit, Access::StorageRead)
      .read(hitNormal, Access::StorageRead)
      .read(hitRadiance, Access::StorageRead)
      .read(neeRadiance, Access::StorageRead)
      .read(neeVisibility, Access::StorageRead)
      .write(candidateEstimate, Access::StorageWrite)
      .write(candidate[0], Access::StorageWrite)
      .write(candidate[1], Access::StorageWrite)
      .write(candidate[2], Access::StorageWrite)
      .write(candidate[3], Access::StorageWrite)
      .write(reservoirValidity, Access::StorageWrite)
      .read(reservoir[0].previous, Access::StorageRead)
      .read(reservoir[1].previous, Access::StorageRead)
      .read(reservoir[2].previous, Access::StorageRead)
      .read(reservoir[3].previous, Access::StorageRead)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        candidates_.record(
            cmd,
            {{gpu::GI_CANDIDATES_BINDING_PREVIOUS + 0, r.image(reservoir[0].previous)},
             {gpu::GI_CANDIDATES_BINDING_PREVIOUS + 1, r.image(reservoir[1].previous)},
             {gpu::GI_CANDIDATES_BINDING_PREVIOUS + 2, r.image(reservoir[2].previous)},
             {gpu::GI_CANDIDATES_BINDING_PREVIOUS + 3, r.image(reservoir[3].previous)},
             {gpu::GI_CANDIDATES_BINDING_VALIDITY, r.image(reservoirValidity)},
             {gpu::GI_CANDIDATES_BINDING_NORMALS, r.image(in.gbuffer.normals)},
             {gpu::GI_CANDIDATES_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
             {gpu::GI_CANDIDATES_BINDING_RAYS, r.image(rays)},
             {gpu::GI_CANDIDATES_BINDING_HIT, r.image(hit)},
             {gpu::GI_CANDIDATES_BINDING_HIT_NORMAL, r.image(hitNormal)},
             {gpu::GI_CANDIDATES_BINDING_HIT_RADIANCE, r.image(hitRadiance)},
             {gpu::GI_CANDIDATES_BINDING_NEE_RADIANCE, r.image(neeRadiance)},
             {gpu::GI_CANDIDATES_BINDING_VISIBILITY, r.image(neeVisibility)},
             {gpu::GI_CANDIDATES_BINDING_SAMPLE, r.image(candidate[0])},
             {gpu::GI_CANDIDATES_BINDING_RADIANCE, r.image(candidate[1])},
             {gpu::GI_CANDIDATES_BINDING_ORIGIN, r.image(candidate[2])},
             {gpu::GI_CANDIDATES_BINDING_RESERVOIR_NORMALS, r.image(candidate[3])},
             {gpu::GI_CANDIDATES_BINDING_ESTIMATE, r.image(candidateEstimate)}},
            passConstants(in, false), gi);
      });
  {
    graph::PassBuilder pass = graph.addPass("gi-restir-temporal", QueueKind::Compute);
    pass.read(in.frame.constants, Access::StorageRead)
        .read(in.gbuffer.normals, Access::StorageRead)
        .read(in.gbuffer.depth.current, Access::StorageRead)
        .read(in.gbuffer.velocity, Access::StorageRead);
    // The first image written is the reservoir's estimate: the pass's debug view.
    pass.write(reservoirEstimate, Access::StorageWrite);
    for (int i = 0; i < 4; ++i)
      pass.read(candidate[i], Access::StorageRead)
          .read(reservoir[i].previous, Access::StorageRead)
          .write(reservoir[i].current, Access::StorageWrite);
    pass.read(reservoirValidity, Access::StorageRead)
        .read(candidateEstimate, Access::StorageRead)
        .read(candidateMean.previous, Access::StorageRead)
        .write(candidateMean.current, Access::StorageWrite);
    // Without the validation pass the occlusion-validity binding gets an unused R16F image.
    graph::ImageHandle occlusion = occlusionValidity ? occlusionValidity->previous : neeVisibility;
    pass.read(occlusion, Access::StorageRead);
    pass.record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
      bool valid = !lightCutPending_;
      for (int i = 0; i < 4; ++i) valid = valid && r.historyValid(reservoir[i]);
      valid = valid && r.historyValid(candidateMean);
      std::vector<ImageBinding> images = {
          {gpu::GI_TEMPORAL_BINDING_VALIDITY, r.image(reservoirValidity)},
          {gpu::GI_TEMPORAL_BINDING_OCCLUSION_VALIDITY, r.image(occlusion)},
          {gpu::GI_TEMPORAL_BINDING_NORMALS, r.image(in.gbuffer.normals)},
          {gpu::GI_TEMPORAL_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
          {gpu::GI_TEMPORAL_BINDING_VELOCITY, r.image(in.gbuffer.velocity)},
          {gpu::GI_TEMPORAL_BINDING_ESTIMATE, r.image(reservoirEstimate)},
          {gpu::GI_TEMPORAL_BINDING_CANDIDATE_ESTIMATE, r.image(candidateEstimate)},
          {gpu::GI_TEMPORAL_BINDING_PREVIOUS_CANDIDATE_MEAN, r.image(candidateMean.previous)},
          {gpu::GI_TEMPORAL_BINDING_CURRENT_CANDIDATE_MEAN, r.image(candidateMean.current)}};
      for (uint32_t i = 0; i < 4; ++i) {
        images.push_back({gpu::GI_TEMPORAL_BINDING_CANDIDATE + i, r.image(candidate[i])});
        images.push_back({gpu::GI_TEMPORAL_BINDING_PREVIOUS + i, r.image(reservoir[i].previous)});
        images.push_back({gpu::GI_TEMPORAL_BINDING_CURRENT + i, r.image(reservoir[i].current)});
      }
      temporal_.record(cmd, images, passConstants(in, valid), gi);
    });
  }
  ReservoirImages temporalReservoir;
  for (int i = 0; i < 4; ++i) temporalReservoir[i] = reservoir[i].current;
  const ReservoirImages final =
      declareSpatialChain(graph, in, temporalReservoir, occlusionValidity);
  // Which of the resolve's samples are hidden from pixels beside an occluder (restir_gi_io.h).
  // Without the pass its binding gets the (R32UI) GBuffer flags, which the shaders then ignore.
  graph::ImageHandle resolveOcclusion =
      settings_.occluderVisibility ? graph.createImage("gi.resolve-occlusion", {VK_FORMAT_R32_UINT})
                                   : in.gbuffer.flags;
  // gi-trace-resolve-visibility and gi-restir-resolve read the same reservoir and GBuffer
  // images (the resolve's bindings) and write one image each; the resolve also reads the
  // occlusion (binding 0: none).
  auto declareResolveStage = [&](const char* name, RestirGiPass& shader, uint32_t outputBinding,
                                 graph::ImageHandle output, uint32_t occlusionBinding) {
    graph::PassBuilder pass = graph.addPass(name, QueueKind::Compute);
    pass.read(in.frame.constants, Access::StorageRead)
        .write(output, Access::StorageWrite)
        .read(in.gbuffer.normals, Access::StorageRead)
        .read(in.gbuffer.depth.current, Access::StorageRead)
        .read(in.gbuffer.flags, Access::StorageRead);
    if (occlusionBinding != 0) pass.read(resolveOcclusion, Access::StorageRead);
    for (int i = 0; i < 4; ++i) pass.read(final[i], Access::StorageRead);
    RestirGiPass* stage = &shader;  // a member: outlives the graph's recorded lambdas
    pass.record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
      std::vector<ImageBinding> images = {
          {gpu::GI_RESOLVE_BINDING_NORMALS, r.image(in.gbuffer.normals)},
          {gpu::GI_RESOLVE_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
          {gpu::GI_RESOLVE_BINDING_FLAGS, r.image(in.gbuffer.flags)},
          {outputBinding, r.image(output)}};
      if (occlusionBinding != 0) images.push_back({occlusionBinding, r.image(resolveOcclusion)});
      for (uint32_t i = 0; i < 4; ++i)
        images.push_back({gpu::GI_RESOLVE_BINDING_RESERVOIR + i, r.image(final[i])});
      stage->record(cmd, images, passConstants(in, false), full);
    });
  };
  if (settings_.occluderVisibility)
    declareResolveStage("gi-trace-resolve-visibility", resolveVisibility_,
                        gpu::GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, resolveOcclusion, 0);
  declareResolveStage("gi-restir-resolve", resolve_, gpu::GI_RESOLVE_BINDING_OUTPUT, resolved,
                      gpu::GI_RESOLVE_BINDING_OCCLUSION);
  if (!denoise) return {output};
  graph::HistoryImage denoised = graph.createHistoryImage("gi.denoised", {kRgba16f});
  graph::HistoryImage denoisedFast = graph.createHistoryImage("gi.denoised-fast", {kRgba16f});
  const bool spatialDenoise = settings_.spatialDenoise;
  // Without the validation pass the occlusion-validity binding gets an unused R16F image.
  graph::ImageHandle occlusionNow = occlusionValidity ? occlusionValidity->current : neeVisibility;
  graph::ImageHandle temporalOut =
      spatialDenoise ? graph.createImage("gi.temporal-denoised", {kRgba16f}) : output;
  graph.addPass("gi-temporal-denoise", QueueKind::Compute)
      .read(in.frame.constants, Access::StorageRead)
      .write(temporalOut, Access::StorageWrite)
      .read(resolved, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(in.gbuffer.depth.previous, Access::StorageRead)
      .read(in.gbuffer.flags, Access::StorageRead)
      .read(in.gbuffer.velocity, Access::StorageRead)
      .read(denoised.previous, Access::StorageRead)
      .read(denoisedFast.previous, Access::StorageRead)
      .read(reservoirValidity, Access::StorageRead)
      .read(occlusionNow, Access::StorageRead)
      .write(denoised.current, Access::StorageWrite)
      .write(denoisedFast.current, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        bool valid = !lightCutPending_ && r.historyValid(denoised) &&
                     r.historyValid(denoisedFast) && r.historyValid(in.gbuffer.depth);
        denoise_.record(cmd,
                        {{gpu::GI_DENOISE_BINDING_INPUT, r.image(resolved)},
                         {gpu::GI_DENOISE_BINDING_NORMALS, r.image(in.gbuffer.normals)},
                         {gpu::GI_DENOISE_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
                         {gpu::GI_DENOISE_BINDING_PREVIOUS_DEPTH, r.image(in.gbuffer.depth.previous)},
                         {gpu::GI_DENOISE_BINDING_FLAGS, r.image(in.gbuffer.flags)},
                         {gpu::GI_DENOISE_BINDING_VELOCITY, r.image(in.gbuffer.velocity)},
                         {gpu::GI_DENOISE_BINDING_PREVIOUS, r.image(denoised.previous)},
                         {gpu::GI_DENOISE_BINDING_CURRENT, r.image(denoised.current)},
                         {gpu::GI_DENOISE_BINDING_OUTPUT, r.image(temporalOut)},
                         {gpu::GI_DENOISE_BINDING_VALIDITY, r.image(reservoirValidity)},
                         {gpu::GI_DENOISE_BINDING_OCCLUSION_VALIDITY, r.image(occlusionNow)},
                         {gpu::GI_DENOISE_BINDING_PREVIOUS_FAST, r.image(denoisedFast.previous)},
                         {gpu::GI_DENOISE_BINDING_CURRENT_FAST, r.image(denoisedFast.current)}},
                        passConstants(in, valid), full);
      });
  if (!spatialDenoise) return {output};
  graph.addPass("gi-spatial-denoise", QueueKind::Compute)
      .write(output, Access::StorageWrite)
      .read(in.frame.constants, Access::StorageRead)
      .read(temporalOut, Access::StorageRead)
      .read(in.gbuffer.normals, Access::StorageRead)
      .read(in.gbuffer.depth.current, Access::StorageRead)
      .read(in.gbuffer.flags, Access::StorageRead)
      .read(resolveOcclusion, Access::StorageRead)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        spatialDenoise_.record(cmd,
                               {{gpu::GI_SPATIAL_DENOISE_BINDING_INPUT, r.image(temporalOut)},
                                {gpu::GI_SPATIAL_DENOISE_BINDING_NORMALS, r.image(in.gbuffer.normals)},
                                {gpu::GI_SPATIAL_DENOISE_BINDING_DEPTH, r.image(in.gbuffer.depth.current)},
                                {gpu::GI_SPATIAL_DENOISE_BINDING_FLAGS, r.image(in.gbuffer.flags)},
                                {gpu::GI_SPATIAL_DENOISE_BINDING_OUTPUT, r.image(output)},
                                {gpu::GI_SPATIAL_DENOISE_BINDING_OCCLUSION, r.image(resolveOcclusion)}},
                               passConstants(in, false), full);
      });
  return {output};
}

}  // namespace bounce
