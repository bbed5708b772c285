#include "denoise/svgf.h"

#include <bit>
#include <cstring>
#include <string>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "core/error.h"

namespace bounce {

using graph::Access;

namespace {

constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
// svgf.surface: depth bits and an octahedral snorm16 normal (denoise/packed_surface.glsl
// packSurface).
constexpr VkFormat kRg32ui = VK_FORMAT_R32G32_UINT;
constexpr uint32_t kMaxIterations = 5;

void dispatch(VkCommandBuffer cmd, const gpu::SvgfConstants& c) {
  vk::ComputePipeline::dispatchCovering(cmd, c.resolution.x, c.resolution.y, gpu::SVGF_GROUP_SIZE,
                                        gpu::SVGF_GROUP_SIZE);
}

}  // namespace

// As packed_surface.glsl's encodeOctahedralNormal / decodeOctahedralNormal.
glm::uvec2 packSvgfSurface(const glm::vec4& normalDepth) {
  glm::vec3 n = glm::vec3(normalDepth);
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  glm::vec2 e(n.x, n.y);
  if (n.z < 0.0f)
    e = (1.0f - glm::abs(glm::vec2(n.y, n.x))) *
        glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
  return {std::bit_cast<uint32_t>(normalDepth.w), glm::packSnorm2x16(e)};
}

glm::vec4 unpackSvgfSurface(const glm::uvec2& texel) {
  const glm::vec2 e = glm::unpackSnorm2x16(texel.y);
  glm::vec3 n(e, 1.0f - std::abs(e.x) - std::abs(e.y));
  if (n.z < 0.0f) {
    const glm::vec2 folded = (1.0f - glm::abs(glm::vec2(n.y, n.x))) *
                             glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
    n.x = folded.x;
    n.y = folded.y;
  }
  return {glm::normalize(n), std::bit_cast<float>(texel.x)};
}

bool isSvgfSurfaceView(const graph::DebugView& view) {
  const std::string& r = view.resource;
  const auto endsWith = [&r](const std::string& tail) {
    return r.size() >= tail.size() && r.compare(r.size() - tail.size(), tail.size(), tail) == 0;
  };
  return view.isImage && view.format == kRg32ui &&
         (endsWith(".surface") || endsWith(".surface.previous"));
}

ImageRGBA32F decodeSvgfSurfaceView(const graph::DebugView& view) {
  const size_t texels = size_t(view.width) * view.height;
  if (view.bytes.size() < texels * sizeof(glm::uvec2))
    fail("debug view '{}': {} bytes for a {}x{} image", view.name, view.bytes.size(), view.width,
         view.height);
  ImageRGBA32F out(int(view.width), int(view.height));
  for (size_t i = 0; i < texels; ++i) {
    glm::uvec2 texel;
    std::memcpy(&texel, view.bytes.data() + sizeof(texel) * i, sizeof(texel));
    const glm::vec4 surface = texel.x == 0u ? glm::vec4(0.0f) : unpackSvgfSurface(texel);
    for (int c = 0; c < 4; ++c) out.pixels[4 * i + size_t(c)] = surface[c];
  }
  return out;
}

void validate(const SvgfSettings& s) {
  if (!(s.colorAlpha > 0.0f && s.colorAlpha <= 1.0f))
    fail("SVGF: colour alpha {} must be in (0, 1]", s.colorAlpha);
  if (!(s.momentsAlpha > 0.0f && s.momentsAlpha <= 1.0f))
    fail("SVGF: moments alpha {} must be in (0, 1]", s.momentsAlpha);
  if (!(s.maxHistory >= 1.0f && s.maxHistory <= 1024.0f))
    fail("SVGF: maximum history {} frames must be 1 to 1024", s.maxHistory);
  if (!(s.depthTolerance > 0.0f) || !(s.normalTolerance >= -1.0f && s.normalTolerance <= 1.0f))
    fail("SVGF: depth tolerance {} must be positive, normal tolerance {} in [-1, 1]",
         s.depthTolerance, s.normalTolerance);
  // Iteration 0 feeds the history and the last writes the output: two passes at least.
  if (s.iterations < 2 || s.iterations > kMaxIterations)
    fail("SVGF: {} à-trous iterations, expected 2 to {}", s.iterations, kMaxIterations);
  if (s.feedbackIteration + 1 >= s.iterations)
    fail("SVGF: feedback iteration {} must be below the last ({}), which remodulates",
         s.feedbackIteration, s.iterations - 1);
  if (!(s.phiDepth > 0.0f) || !(s.phiNormal >= 0.0f) || !(s.phiLuminance > 0.0f))
    fail("SVGF: edge stops (depth {}, normal {}, luminance {}) must be positive", s.phiDepth,
         s.phiNormal, s.phiLuminance);
}

Svgf::Svgf(vk::Context& context, const GpuScene& scene, const SvgfSettings& settings,
           std::string name)
    : settings_(settings),
      name_(std::move(name)),
      temporal_(context, scene, "denoise/svgf_temporal", gpu::SVGF_TEMPORAL_BINDING_COUNT,
                sizeof(gpu::SvgfConstants)),
      variance_(context, scene, "denoise/svgf_variance", gpu::SVGF_VARIANCE_BINDING_COUNT,
                sizeof(gpu::SvgfConstants)),
      atrous_(context, scene, "denoise/svgf_atrous", gpu::SVGF_ATROUS_BINDING_COUNT,
              sizeof(gpu::SvgfConstants), kMaxIterations) {
  validate(settings_);
}

gpu::SvgfConstants Svgf::constants(VkExtent2D resolution, const SvgfInputs& in) const {
  const SvgfSettings& s = settings_;
  gpu::SvgfConstants c{};
  c.resolution = {resolution.width, resolution.height};
  c.flags =
      (in.octahedralNormals ? gpu::SVGF_FLAG_OCTAHEDRAL_NORMALS : 0u) |
      (in.albedo ? gpu::SVGF_FLAG_ALBEDO : 0u) |
      (s.luminanceStop == SvgfLuminanceStop::Shared ? gpu::SVGF_FLAG_SHARED_LUMINANCE_STOP : 0u) |
      (s.kernel == SvgfKernel::Gaussian3x3 ? gpu::SVGF_FLAG_KERNEL_3X3 : 0u) |
      (s.prefilterEveryIteration ? 0u : gpu::SVGF_FLAG_PREFILTER_FIRST_ONLY);
  c.colorAlpha = s.colorAlpha;
  c.momentsAlpha = s.momentsAlpha;
  c.depthTolerance = s.depthTolerance;
  c.normalTolerance = s.normalTolerance;
  c.phiDepth = s.phiDepth;
  c.phiNormal = s.phiNormal;
  c.phiLuminance = s.phiLuminance;
  c.maxHistory = s.maxHistory;
  c.varianceHistoryFrames = s.varianceHistoryFrames;
  return c;
}

graph::ImageHandle Svgf::declare(graph::FrameGraph& graph, VkExtent2D resolution,
                                 const SvgfInputs& in, graph::ImageHandle output) {
  const Temporal temporal = declareTemporal(graph, resolution, in);
  declareSpatial(graph, resolution, in, temporal, output);
  return temporal.moments;
}

Svgf::Temporal Svgf::declareTemporal(graph::FrameGraph& graph, VkExtent2D resolution,
                                     const SvgfInputs& in) {
  graph::HistoryImage surface = graph.createHistoryImage(name_ + ".surface", {kRg32ui});
  graph::HistoryImage moments = graph.createHistoryImage(name_ + ".moments", {kRgba32f});
  graph::HistoryImage illumination = graph.createHistoryImage(name_ + ".illumination", {kRgba16f});
  graph::ImageHandle accumulated = graph.createImage(name_ + ".accumulated", {kRgba16f});
  graph::ImageHandle filtered = graph.createImage(name_ + ".filtered-moments", {kRgba16f});
  graph::ImageHandle slope = graph.createImage(name_ + ".slope", {VK_FORMAT_R32_SFLOAT});
  const graph::BufferHandle tiles =
      graph.createBuffer(name_ + ".variance-tiles",
                         {graph::BufferSize::perPixel(sizeof(uint32_t), gpu::SVGF_GROUP_SIZE)
                              .withHeader(sizeof(gpu::SvgfVarianceTilesHeader))});
  const gpu::SvgfConstants c = constants(resolution, in);

  graph.addPass(name_ + "-variance-tiles-reset", graph::QueueKind::Compute)
      .write(tiles, Access::TransferDst)
      .record([tiles](VkCommandBuffer cmd, const graph::PassResources& r) {
        const gpu::SvgfVarianceTilesHeader empty{0u, 1u, 1u, 0u};  // no tile yet
        vkCmdUpdateBuffer(cmd, r.buffer(tiles).buffer, 0, sizeof(empty), &empty);
      });

  graph::PassBuilder t = graph.addPass(name_ + "-temporal", graph::QueueKind::Compute);
  t.read(in.noisy, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_NOISY)
      .read(in.depth, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_DEPTH)
      .read(in.normals, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_NORMALS)
      .read(in.motion, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_MOTION)
      .read(surface.previous, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_PREVIOUS_SURFACE)
      .read(moments.previous, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_PREVIOUS_MOMENTS)
      .read(illumination.previous, Access::StorageRead,
            gpu::SVGF_TEMPORAL_BINDING_PREVIOUS_ILLUMINATION)
      .write(surface.current, Access::StorageWrite, gpu::SVGF_TEMPORAL_BINDING_SURFACE)
      .write(moments.current, Access::StorageWrite, gpu::SVGF_TEMPORAL_BINDING_MOMENTS)
      .write(accumulated, Access::StorageWrite, gpu::SVGF_TEMPORAL_BINDING_ACCUMULATED)
      .write(slope, Access::StorageWrite, gpu::SVGF_TEMPORAL_BINDING_SLOPE)
      .write(filtered, Access::StorageWrite, gpu::SVGF_TEMPORAL_BINDING_FILTERED)
      .write(tiles, Access::StorageReadWrite);
  if (in.albedo)
    t.read(*in.albedo, Access::StorageRead, gpu::SVGF_TEMPORAL_BINDING_ALBEDO);
  else
    t.readPlaceholder(in.noisy, gpu::SVGF_TEMPORAL_BINDING_ALBEDO);
  const bool drop = in.dropHistory;
  t.record([this, c, drop, surface, moments, illumination, tiles](VkCommandBuffer cmd,
                                                                  const graph::PassResources& r) {
    gpu::SvgfConstants k = c;
    k.varianceTiles = r.buffer(tiles).address;
    k.historyValid =
        !drop && r.historyValid(surface) && r.historyValid(moments) && r.historyValid(illumination);
    temporal_.bind(cmd, k, r);
    dispatch(cmd, k);
  });

  graph.addPass(name_ + "-variance", graph::QueueKind::Compute)
      .read(accumulated, Access::StorageRead, gpu::SVGF_VARIANCE_BINDING_ACCUMULATED)
      .read(moments.current, Access::StorageRead, gpu::SVGF_VARIANCE_BINDING_MOMENTS)
      .read(surface.current, Access::StorageRead, gpu::SVGF_VARIANCE_BINDING_SURFACE)
      .read(slope, Access::StorageRead, gpu::SVGF_VARIANCE_BINDING_SLOPE)
      .read(tiles, Access::StorageRead)
      .read(tiles, Access::IndirectRead)
      // The listed tiles' short histories only: svgf-temporal wrote the other pixels.
      .write(filtered, Access::StorageWrite, gpu::SVGF_VARIANCE_BINDING_OUTPUT)
      .record([this, c, tiles](VkCommandBuffer cmd, const graph::PassResources& r) {
        gpu::SvgfConstants k = c;
        k.varianceTiles = r.buffer(tiles).address;
        variance_.bind(cmd, k, r);
        vkCmdDispatchIndirect(cmd, r.buffer(tiles).buffer, 0);
      });

  return {filtered, surface.current, slope, moments.current, illumination.current};
}

void Svgf::declareSpatial(graph::FrameGraph& graph, VkExtent2D resolution, const SvgfInputs& in,
                          const Temporal& temporal, graph::ImageHandle output,
                          std::optional<graph::ImageHandle> tiles) {
  const gpu::SvgfConstants c = constants(resolution, in);
  // Iteration feedbackIteration writes the colour history; the last writes `output`.
  graph::ImageHandle input = temporal.filtered;
  const graph::ImageHandle albedo = in.albedo ? *in.albedo : in.noisy;
  for (uint32_t i = 0; i < settings_.iterations; ++i) {
    graph::ImageHandle target =
        i + 1 == settings_.iterations
            ? output
            : (i == settings_.feedbackIteration
                   ? temporal.illumination
                   : graph.createImage(name_ + ".atrous-" + std::to_string(i), {kRgba16f}));
    declareAtrous(graph, c, input, temporal.surface, temporal.slope, albedo, i, target, tiles);
    input = target;
  }
}

void Svgf::declareAtrous(graph::FrameGraph& graph, const gpu::SvgfConstants& constants,
                         graph::ImageHandle input, graph::ImageHandle surface,
                         graph::ImageHandle slope, graph::ImageHandle albedo, uint32_t iteration,
                         graph::ImageHandle output, std::optional<graph::ImageHandle> tiles) {
  gpu::SvgfConstants c = constants;
  if (tiles) c.flags |= gpu::SVGF_FLAG_TILES;
  c.step = 1u << iteration;
  c.iteration = iteration;
  c.lastIteration = iteration + 1 == settings_.iterations ? 1u : 0u;
  graph::PassBuilder pass =
      graph.addPass(name_ + "-atrous-" + std::to_string(iteration), graph::QueueKind::Compute);
  pass.read(input, Access::StorageRead, gpu::SVGF_ATROUS_BINDING_INPUT)
      .read(surface, Access::StorageRead, gpu::SVGF_ATROUS_BINDING_SURFACE)
      .read(slope, Access::StorageRead, gpu::SVGF_ATROUS_BINDING_SLOPE)
      .write(output, Access::StorageWrite, gpu::SVGF_ATROUS_BINDING_OUTPUT);
  if (c.lastIteration && (c.flags & gpu::SVGF_FLAG_ALBEDO))
    pass.read(albedo, Access::StorageRead, gpu::SVGF_ATROUS_BINDING_ALBEDO);
  else
    pass.readPlaceholder(input, gpu::SVGF_ATROUS_BINDING_ALBEDO);
  if (tiles)
    pass.read(*tiles, Access::StorageRead, gpu::SVGF_ATROUS_BINDING_TILES);
  else
    pass.readPlaceholder(input, gpu::SVGF_ATROUS_BINDING_TILES);
  pass.record([this, c](VkCommandBuffer cmd, const graph::PassResources& r) {
    atrous_.bind(cmd, c, r, c.iteration);
    dispatch(cmd, c);
  });
}

void Svgf::declareAtrousStep(graph::FrameGraph& graph, VkExtent2D resolution,
                             graph::ImageHandle input, graph::ImageHandle surface,
                             graph::ImageHandle slope, uint32_t iteration,
                             graph::ImageHandle output) {
  if (iteration >= kMaxIterations)
    fail("SVGF: à-trous iteration {} of {}", iteration, kMaxIterations);
  SvgfInputs none;
  declareAtrous(graph, constants(resolution, none), input, surface, slope, input, iteration,
                output);
}

}  // namespace bounce
