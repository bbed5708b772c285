// The scene's lights as next-event estimation samples them, gathered on the CPU once per scene
// for the reference path tracer and the real-time frame alike (see shared/lighting_io.h for the
// GPU layout):
//   - distant lights: the sun and KHR directional lights;
//   - local lights: every emissive triangle of every instance, in world space, and the KHR
//     point and spot lights, with an alias table that picks one in proportion to its power.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rt/scene_bvh.h"
#include "scene/scene.h"
#include "shared/lighting_io.h"

namespace bounce {

struct LightTable {
  std::vector<gpu::GpuEmissiveTriangle> emissiveTriangles;
  std::vector<gpu::GpuPunctualLight> punctualLights;
  std::vector<gpu::GpuLightAlias> alias;  // emissive triangles first, then punctual lights
  std::vector<gpu::GpuDistantLight> distantLights;
  std::vector<float> materialLightAreaPdf;   // per Scene::materials entry, see lighting_io.h
  std::vector<double> materialEmissiveArea;  // per Scene::materials entry: m^2 of its emitters
  double totalLocalPower = 0.0;              // W (luminance-weighted), the alias table's sum
  // CPU-side facts updateLightTable() needs to recompute the entries in place: the instance of
  // each emissive triangle, the Scene::lights index of each punctual light, and each
  // material's sampled emitted luminance (0 for materials left out).
  std::vector<uint32_t> emissiveTriangleInstance;
  std::vector<uint32_t> punctualLightSource;
  std::vector<float> materialLuminance;

  uint32_t localLightCount() const { return uint32_t(alias.size()); }
};

// Shared-exponent RGB (RGB9E5, EXT_texture_shared_exponent) in one word, as
// GpuEmissiveTriangle::meanEmission stores it; a positive channel stays positive.
uint32_t encodeRgb9e5(const glm::vec3& rgb);
glm::vec3 decodeRgb9e5(uint32_t bits);

// Rec. 709 luminance of linear RGB.
float luminance(const glm::vec3& rgb);

// The mean emitted radiance of a material over its surface: emissive factor x the mean of its
// emissive texture (decoded from sRGB). This is what light selection weighs triangles by.
glm::vec3 meanEmission(const Scene& scene, const Material& material);

// Power (luminance-weighted flux) each light contributes to the selection, in watts:
//   emissive triangle   pi * area * luminance(mean emission)   (one side emits)
//   point light         4 pi * luminance(intensity * colour)
//   spot light          2 pi (1 - cos outerConeAngle) * luminance(intensity * colour)
// The spot's is the flux of its full cone without the falloff: an estimate, which only steers
// selection (any positive weight keeps the estimator unbiased).
double punctualLightPower(const PunctualLight& light);

// Walker's alias table (Walker 1977) built with Vose's stable method (Vose 1991, "A Linear
// Algorithm for Generating Random Numbers with a Given Distribution"): entry i is chosen with
// probability weights[i] / sum. Weights must be finite and >= 0 with a positive sum.
std::vector<gpu::GpuLightAlias> buildAliasTable(std::span<const double> weights);

// Everything above for a scene whose BVH arrays (instance transforms, vertex streams) are
// `bvh`, exactly as the GPU sees them. Throws bounce::Error when the scene has more distant
// lights than MAX_DISTANT_LIGHTS. Materials flagged in `unsampledMaterials` (indexed
// like Scene::materials; empty = none) are left out of the local lights: their triangles are
// never picked and their materialLightAreaPdf is 0, so MIS counts BRDF hits on them in full.
//
// Every KHR point and spot light gets an entry, a switched-off one (intensity 0) too, with
// power 0 (never picked): the table's layout (which entry is which light) depends on the scene
// only, never on the lights' state, so updateLightTable() can rewrite it in place.
LightTable buildLightTable(const Scene& scene, const rt::SceneBvh& bvh,
                           const std::vector<bool>& unsampledMaterials = {});

// Rewrites `table` (built by buildLightTable for this scene) in place for the lights' current
// state: emissive triangles moved with their instances' current transforms in `bvh`, punctual
// lights from `lights` (the scene's lights, moved, dimmed or switched off; the same count and
// types as Scene::lights), the alias table, the total power and materialLightAreaPdf. Every
// entry keeps its index and no vector changes size. When every light is off the alias table is
// all zeros and totalLocalPower 0: nothing is to be picked.
void updateLightTable(LightTable& table, std::span<const PunctualLight> lights,
                      const rt::SceneBvh& bvh);

// The map from a ray hit to the light-table entry of the emissive triangle it hit, for
// consumers that meet lights through BRDF-sampled rays (ReSTIR DI's BRDF candidate). One uint
// array in three levels, all indices into the same array:
//   [instance]                      first geometry slot of the instance, or kNoLightEntry
//   [slot + local geometry]         first triangle slot of that geometry, or kNoLightEntry
//   [triangle slot + primitive]     the emissive triangle's light-table index, or kNoLightEntry
// Only instances and geometries with an entry get slots. Depends on the layout only (built
// once per scene: updateLightTable keeps it valid).
inline constexpr uint32_t kNoLightEntry = 0xFFFFFFFFu;
std::vector<uint32_t> buildEmissiveHitMap(const LightTable& table, const rt::SceneBvh& bvh);

}  // namespace bounce
