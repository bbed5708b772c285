#include "gi/lux/lux_gi.h"

#include <span>

#include "core/error.h"
#include "gi/evolve/restir/restir_gi.h"

namespace bounce {

using graph::Access;
using graph::QueueKind;

namespace {

constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;

void recordPass(ComputePass& pass, VkCommandBuffer cmd, const graph::PassResources& r,
                const gpu::LuxPassConstants& constants, VkExtent2D extent) {
  pass.bind(cmd, constants, r);
  vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::RESTIR_GI_GROUP_SIZE,
                                        gpu::RESTIR_GI_GROUP_SIZE);
}

}  // namespace

void validate(const LuxSettings& s) {
  if (s.candidates < 1 || s.candidates > 64)
    fail("Lux: {} candidates per pixel; expected 1 to 64", s.candidates);
  if (!(s.targetFloor > 0.0f && s.targetFloor <= 10.0f))
    fail("Lux: target floor {}; expected (0, 10]", s.targetFloor);
  if (!(s.maxJacobian >= 1.0f && s.maxJacobian <= 1000.0f))
    fail("Lux: maximum Jacobian {}; expected 1 to 1000", s.maxJacobian);
  if (s.integralSamples > 256)
    fail("Lux: {} probe-integral samples; expected 0 to 256", s.integralSamples);
}

RestirGiSettings LuxGi::reuseSettings(RestirGiSettings s, const LuxSettings& lux) {
  s.maxJacobian = lux.maxJacobian;
  s.temporalProducerNormalisation = true;
  s.canonicalResolve = lux.unbiasedReuse;
  s.secondVertex = RestirGiSecondVertex::Cache;  // the probe field at the hit
  s.validationPeriod = 0;                        // lux-candidates traces no validation rays
  s.denoiser = GiDenoiser::None;                 // LuxSettings::svgf instead
  s.temporalDenoise = false;
  s.spatialDenoise = false;
  return s;
}

LuxGi::LuxGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
             const LuxSettings& settings, const RestirGiSettings& reuse,
             const ClipmapCacheSettings& cache, VkExtent2D resolution)
    : settings_(settings),
      reuse_(reuseSettings(reuse, settings)),
      lights_(context, gpuScene, scene),
      cache_(context, gpuScene, lights_, cache),
      candidates_(context, gpuScene, "gi/lux/lux_candidates", gpu::LUX_CANDIDATES_BINDING_COUNT,
                  sizeof(gpu::LuxPassConstants)),
      resolveCandidates_(context, gpuScene, "gi/lux/lux_resolve_candidates",
                         gpu::LUX_RESOLVE_BINDING_COUNT, sizeof(gpu::LuxPassConstants)),
      integral_(context, gpuScene, "gi/lux/lux_probe_integral", gpu::LUX_INTEGRAL_BINDING_COUNT,
                sizeof(gpu::LuxPassConstants)),
      trace_(context, gpuScene, secondVertexConstant(reuse_.secondVertex)),
      temporal_(context, gpuScene),
      spatial_(context, gpuScene, reuse_),
      resolve_(context, gpuScene, reuse_) {
  validate(settings_);
  validate(reuse_);
  settleFramesLeft_ = reuse_.settleFrames;  // the first frames: the probe field starts empty
  if (settings_.svgf) svgf_ = std::make_unique<Svgf>(context, gpuScene, reuse_.svgf);
  giResolution_ = graph::ImageSize::dividedRes(reuse_.divisor).resolve(resolution);
  const gpu::RestirGiConstants c = restirGiConstants(reuse_, giResolution_, lights_.address(),
                                                     cache_.constantsAddress(), 0, false);
  constants_ = vk::uploadBuffer(context, std::as_bytes(std::span(&c, 1)),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "lux.constants");
}

void LuxGi::afterFrame() {
  cache_.afterFrame();
  lightCutPending_ = false;
  if (settleFramesLeft_ > 0) --settleFramesLeft_;
}

void LuxGi::resetHistory() {
  cache_.resetHistory();
  settleFramesLeft_ = reuse_.settleFrames;
}

void LuxGi::lightingCut() {
  cache_.beginFullRefresh();
  lightCutPending_ = true;
  settleFramesLeft_ = reuse_.settleFrames;
}

gpu::LuxPassConstants LuxGi::passConstants(const RestirFrame& f) const {
  gpu::LuxPassConstants c{};
  c.frame = f.in.frame.constantsAddress;
  c.gi = f.constants;
  c.candidates = settings_.candidates;
  c.targetFloor = settings_.targetFloor;
  c.integralSamples = settings_.integralSamples;
  c.integralUniform = settings_.integralUniform ? 1u : 0u;
  return c;
}

RestirFrame LuxGi::beginFrame(const GiInputs& inputs) {
  RestirFrame f;
  f.in = inputs;
  f.giSize = graph::ImageSize::dividedRes(reuse_.divisor);
  f.giResolution = giResolution_;
  f.constants = constants_.address();
  f.historyScale = settleFramesLeft_ > 0 ? reuse_.settleHistoryScale : 1.0f;
  f.lightCutPending = lightCutPending_;
  return f;
}

// The chain, top to bottom (lux_gi.h).
DiffuseGiOutput LuxGi::declare(graph::FrameGraph& graph, const GiInputs& in) {
  graph::ImageHandle output = createOutput(graph);
  cache_.declareUpdate(graph, in);
  RestirFrame f = beginFrame(in);
  f.rayLists = declareRayLists(graph);
  const ReservoirHistory history = createReservoirHistory(graph, f.giSize);
  std::optional<graph::HistoryImage> occlusionValidity;
  if (reuse_.spatialReuse && reuse_.spatialValidation)
    occlusionValidity =
        graph.createHistoryImage("gi.spatial-occlusion-validity", {VK_FORMAT_R16_SFLOAT, f.giSize});
  Rays rays = declareCandidates(graph, f);
  GiHits hits = declareGiTrace(graph, f, rays.rays, &cache_, trace_);
  if (settings_.integralSamples > 0) declareProbeIntegral(graph, f);
  cache_.declareStatisticsReadback(graph);  // after the last pass that looks the cache up
  Candidates candidates = declareResolveCandidates(graph, f, rays, hits);
  Reservoirs temporal = temporal_.declare(graph, f, candidates, history, occlusionValidity);
  Reservoirs reservoirs = spatial_.declare(graph, f, temporal, occlusionValidity);
  graph::ImageHandle target =
      svgf_ ? graph.createImage("gi.resolved", {VK_FORMAT_R16G16B16A16_SFLOAT}) : output;
  ResolvedGi resolved = resolve_.declare(graph, f, reservoirs, target);
  if (svgf_) {
    // gi.resolved is radiance per unit albedo already (gi/diffuse_gi.h): no demodulation.
    const GBuffer& g = in.gbuffer;
    SvgfInputs s{resolved.diffuse, g.depth.current, g.normals, g.velocity};
    s.octahedralNormals = true;
    s.dropHistory = f.lightCutPending || settleFramesLeft_ > 0;
    svgf_->declare(graph, in.frame.resolution, s, output);
  }
  return {output};
}

// The probe's irradiance (lux.target) is the first image written: the pass's debug view.
LuxGi::Rays LuxGi::declareCandidates(graph::FrameGraph& graph, const RestirFrame& f) {
  Rays out;
  graph::ImageHandle target = graph.createImage("lux.target", {kRgba16f, f.giSize});
  out.rays = graph.createImage("gi.rays", {kRgba32f, f.giSize});
  out.weight = graph.createImage("lux.weight", {VK_FORMAT_R32_SFLOAT, f.giSize});
  const GBuffer& g = f.in.gbuffer;
  const gpu::LuxPassConstants push = passConstants(f);
  cache_.declareLookup(graph.addPass("lux-candidates", QueueKind::Compute))
      .read(f.in.frame.constants, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::LUX_CANDIDATES_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::LUX_CANDIDATES_BINDING_DEPTH)
      .read(g.flags, Access::StorageRead, gpu::LUX_CANDIDATES_BINDING_FLAGS)
      .write(target, Access::StorageWrite, gpu::LUX_CANDIDATES_BINDING_TARGET)
      .write(out.rays, Access::StorageWrite, gpu::LUX_CANDIDATES_BINDING_RAYS)
      .write(out.weight, Access::StorageWrite, gpu::LUX_CANDIDATES_BINDING_WEIGHT)
      .record([this, f, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        recordPass(candidates_, cmd, r, push, f.giResolution);
      });
  return out;
}

// The candidate's estimate is the first image written: the pass's debug view.
Candidates LuxGi::declareResolveCandidates(graph::FrameGraph& graph, const RestirFrame& f,
                                           const Rays& rays, const GiHits& hits) {
  Candidates c;
  c.estimate = graph.createImage("gi.candidate-estimate", {kRgba16f, f.giSize});
  c.reservoir = createReservoirImages(graph, "gi.candidate.", f.giSize);
  c.validity = graph.createImage("gi.reservoir-validity", {kRgba16f, f.giSize});
  c.neeVisibility = hits.neeVisibility;
  const gpu::LuxPassConstants push = passConstants(f);
  graph::PassBuilder pass = graph.addPass("lux-resolve-candidates", QueueKind::Compute);
  pass.read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.gbuffer.normals, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_NORMALS)
      .read(f.in.gbuffer.depth.current, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_DEPTH)
      .read(rays.rays, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_RAYS)
      .read(rays.weight, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_WEIGHT)
      .read(hits.hit, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_HIT)
      .read(hits.normal, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_HIT_NORMAL)
      .read(hits.radiance, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_HIT_RADIANCE)
      .read(hits.neeRadiance, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_NEE_RADIANCE)
      .read(hits.neeVisibility, Access::StorageRead, gpu::LUX_RESOLVE_BINDING_VISIBILITY)
      .write(c.estimate, Access::StorageWrite, gpu::LUX_RESOLVE_BINDING_ESTIMATE);
  for (uint32_t i = 0; i < 4; ++i)
    pass.write(c.reservoir[i], Access::StorageWrite, gpu::LUX_RESOLVE_BINDING_SAMPLE + i);
  pass.write(c.validity, Access::StorageWrite, gpu::LUX_RESOLVE_BINDING_VALIDITY)
      .record([this, f, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        recordPass(resolveCandidates_, cmd, r, push, f.giResolution);
      });
  return c;
}

void LuxGi::declareProbeIntegral(graph::FrameGraph& graph, const RestirFrame& f) {
  graph::ImageHandle out = graph.createImage("lux.probe-integral", {kRgba32f, f.giSize});
  const GBuffer& g = f.in.gbuffer;
  const gpu::LuxPassConstants push = passConstants(f);
  cache_.declareLookup(graph.addPass("lux-probe-integral", QueueKind::Compute))
      .read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.frame.instances, Access::StorageRead)
      .read(f.in.frame.tlas, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::LUX_INTEGRAL_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::LUX_INTEGRAL_BINDING_DEPTH)
      .read(g.flags, Access::StorageRead, gpu::LUX_INTEGRAL_BINDING_FLAGS)
      .write(out, Access::StorageWrite, gpu::LUX_INTEGRAL_BINDING_OUTPUT)
      .record([this, f, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        recordPass(integral_, cmd, r, push, f.giResolution);
      });
}

}  // namespace bounce
