#include "lighting/light_table.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "scene/texture_pack.h"

namespace bounce {

namespace {

constexpr double kPi = std::numbers::pi;

// transformPoint of shaders/rt/scene.glsl: the same float operations, so that CPU-side light
// geometry matches what the GPU computes at a hit.
glm::vec3 transformPoint(const glm::vec4 (&rows)[3], const glm::vec3& p) {
  return {glm::dot(glm::vec3(rows[0]), p) + rows[0].w, glm::dot(glm::vec3(rows[1]), p) + rows[1].w,
          glm::dot(glm::vec3(rows[2]), p) + rows[2].w};
}

// The tracer flips frontFacing for instances whose transform mirrors (scene_bvh.h).
bool mirrors(const gpu::GpuInstance& instance) {
  const glm::vec4* w = instance.worldToObject;
  return glm::dot(glm::vec3(w[0]), glm::cross(glm::vec3(w[1]), glm::vec3(w[2]))) < 0.0f;
}

glm::vec3 meanTextureColor(const Image& image) {
  glm::dvec3 sum(0.0);
  const size_t texels = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < texels; ++i)
    for (int c = 0; c < 3; ++c) sum[c] += srgb8ToLinear(image.rgba[4 * i + size_t(c)]);
  return texels ? glm::vec3(sum / double(texels)) : glm::vec3(1.0f);
}

struct LocalLights {
  std::vector<gpu::GpuEmissiveTriangle> triangles;
  std::vector<double> trianglePower;
  std::vector<uint32_t> triangleInstance;
};

// Triangle `primitive` of global geometry `global` placed by `instance`, in world space; its
// area is 0 (and its normal 0) where the placement makes it degenerate.
gpu::GpuEmissiveTriangle placeEmissiveTriangle(const rt::SceneBvh& bvh,
                                               const gpu::GpuInstance& instance, uint32_t global,
                                               uint32_t primitive) {
  const gpu::GpuGeometry& g = bvh.geometries.at(global);
  glm::vec3 p[3];
  for (uint32_t k = 0; k < 3; ++k) {
    uint32_t vertex = bvh.indices[g.firstIndex + 3 * primitive + k] + g.vertexOffset;
    p[k] = transformPoint(instance.objectToWorld, bvh.positions[vertex]);
  }
  gpu::GpuEmissiveTriangle t{};
  t.p0 = p[0];
  t.edge1 = p[1] - p[0];
  t.edge2 = p[2] - p[0];
  t.geometry = global;
  t.primitive = primitive;
  glm::vec3 normal = glm::cross(t.edge1, t.edge2);
  float twiceArea = glm::length(normal);
  if (!(twiceArea > 0.0f) || !std::isfinite(twiceArea)) return t;
  t.area = 0.5f * twiceArea;
  t.frontNormal = (mirrors(instance) ? -1.0f : 1.0f) * normal / twiceArea;
  return t;
}

// Every emissive triangle of every instance, in world space.
LocalLights gatherEmissiveTriangles(const Scene& scene, const rt::SceneBvh& bvh,
                                    const std::vector<glm::vec3>& materialEmission,
                                    const std::vector<float>& materialLuminance) {
  LocalLights out;
  for (uint32_t i = 0; i < bvh.instances.size(); ++i) {
    const gpu::GpuInstance& instance = bvh.instances[i];
    const Mesh& mesh = scene.meshes.at(instance.mesh);
    for (uint32_t local = 0; local < mesh.geometries.size(); ++local) {
      const uint32_t global = instance.geometryBase + local;
      const gpu::GpuGeometry& g = bvh.geometries.at(global);
      const float emittedLuminance = materialLuminance.at(g.material);
      if (!(emittedLuminance > 0.0f)) continue;
      for (uint32_t primitive = 0; primitive < g.triangleCount; ++primitive) {
        gpu::GpuEmissiveTriangle t = placeEmissiveTriangle(bvh, instance, global, primitive);
        if (!(t.area > 0.0f)) continue;  // no ray can hit it
        t.meanEmission = encodeRgb9e5(materialEmission.at(g.material));
        out.triangles.push_back(t);
        out.trianglePower.push_back(kPi * double(t.area) * double(emittedLuminance));
        out.triangleInstance.push_back(i);
      }
    }
  }
  return out;
}

gpu::GpuPunctualLight makePunctualLight(const PunctualLight& light) {
  gpu::GpuPunctualLight p{};
  p.position = light.position;
  p.intensity = light.intensity * light.color;
  p.spotDirection = glm::normalize(light.direction);
  if (light.type == PunctualLight::Type::Spot) {
    // The glTF KHR_lights_punctual reference falloff.
    p.type = gpu::PUNCTUAL_LIGHT_SPOT;
    float cosOuter = std::cos(light.outerConeAngle);
    float cosInner = std::cos(light.innerConeAngle);
    p.angleScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    p.angleOffset = -cosOuter * p.angleScale;
  } else {
    p.type = gpu::PUNCTUAL_LIGHT_POINT;
    p.angleScale = 0.0f;
    p.angleOffset = 1.0f;
  }
  return p;
}

// A light at infinity with irradiance E (on a surface facing it), seen as a disc of the given
// angular diameter. The disc's radiance is E / (pi sin^2 theta_max), the value for which a
// surface facing it receives exactly E (and a surface tilted by theta, with the whole disc
// above its horizon, exactly E cos theta); sampling the cone's solid angle
// 2 pi (1 - cos theta_max) uniformly gives coneWeight = E * 2 / (1 + cos theta_max).
gpu::GpuDistantLight makeDistantLight(const glm::vec3& travelDirection, const glm::vec3& irradiance,
                                      float angularDiameterDegrees) {
  gpu::GpuDistantLight d{};
  d.towardLight = -glm::normalize(travelDirection);
  double halfAngle = 0.5 * double(angularDiameterDegrees) * kPi / 180.0;
  d.cosHalfAngle = halfAngle > 0.0 ? float(std::cos(halfAngle)) : 1.0f;
  d.coneWeight =
      d.cosHalfAngle < 1.0f ? irradiance * float(2.0 / (1.0 + std::cos(halfAngle))) : irradiance;
  return d;
}

std::vector<gpu::GpuDistantLight> gatherDistantLights(const Scene& scene) {
  std::vector<gpu::GpuDistantLight> lights;
  if (scene.sun.irradiance > 0.0f)
    lights.push_back(makeDistantLight(scene.sun.direction, scene.sun.irradiance * scene.sun.color,
                                      scene.sun.angularDiameterDegrees));
  for (const PunctualLight& l : scene.lights)
    if (l.type == PunctualLight::Type::Directional && l.intensity > 0.0f)
      lights.push_back(makeDistantLight(l.direction, l.intensity * l.color, 0.0f));
  if (lights.size() > gpu::MAX_DISTANT_LIGHTS)
    fail("{}: {} distant lights (sun and directional lights); the light table takes at most {}",
         scene.name, lights.size(), gpu::MAX_DISTANT_LIGHTS);
  return lights;
}

// The alias table, total power and materialLightAreaPdf of `power` (one entry per local light).
void setLocalPower(LightTable& table, const std::vector<double>& power) {
  table.totalLocalPower = 0.0;
  for (double p : power) table.totalLocalPower += p;
  table.materialLightAreaPdf.assign(table.materialLuminance.size(), 0.0f);
  if (!(table.totalLocalPower > 0.0)) {
    table.alias.assign(power.size(), gpu::GpuLightAlias{});
    table.totalLocalPower = 0.0;
    return;
  }
  table.alias = buildAliasTable(power);
  for (size_t m = 0; m < table.materialLuminance.size(); ++m)
    table.materialLightAreaPdf[m] =
        float(kPi * double(table.materialLuminance[m]) / table.totalLocalPower);
}

}  // namespace

// EXT_texture_shared_exponent's encoding (9-bit mantissas, a 5-bit exponent biased by 15). A
// colour with a positive channel keeps a non-zero mantissa there, so that a light's estimate is
// never 0 where the light emits (a target function must be positive wherever light arrives).
uint32_t encodeRgb9e5(const glm::vec3& rgb) {
  constexpr int kMantissaBits = 9, kBias = 15, kMaxExponent = 31;
  const float largest = 511.0f / 512.0f * std::ldexp(1.0f, kMaxExponent - kBias);
  glm::vec3 c = glm::clamp(rgb, glm::vec3(0.0f), glm::vec3(largest));
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(rgb[k])) c[k] = rgb[k] > 0.0f ? largest : 0.0f;
  const float m = std::max(c.x, std::max(c.y, c.z));
  if (!(m > 0.0f)) return 0u;
  int exponent = std::max(-kBias - 1, int(std::floor(std::log2(m)))) + 1 + kBias;
  float scale = std::ldexp(1.0f, exponent - kBias - kMantissaBits);
  if (std::floor(m / scale + 0.5f) >= 512.0f) scale *= 2.0f, ++exponent;
  uint32_t bits = uint32_t(exponent) << 27;
  for (int k = 0; k < 3; ++k) {
    uint32_t mantissa = uint32_t(std::min(std::floor(c[k] / scale + 0.5f), 511.0f));
    if (c[k] > 0.0f) mantissa = std::max(mantissa, 1u);
    bits |= mantissa << (9 * k);
  }
  return bits;
}

glm::vec3 decodeRgb9e5(uint32_t bits) {
  const float scale = std::ldexp(1.0f, int(bits >> 27) - 15 - 9);
  return glm::vec3(float(bits & 511u), float((bits >> 9) & 511u), float((bits >> 18) & 511u)) *
         scale;
}

float luminance(const glm::vec3& rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

glm::vec3 meanEmission(const Scene& scene, const Material& material) {
  glm::vec3 e = material.emissive;
  if (material.emissiveTexture >= 0 && glm::any(glm::greaterThan(e, glm::vec3(0.0f))))
    e *= meanTextureColor(scene.images.at(size_t(material.emissiveTexture)));
  return e;
}

double punctualLightPower(const PunctualLight& light) {
  double intensity = double(luminance(light.intensity * light.color));
  if (light.type == PunctualLight::Type::Spot)
    return 2.0 * kPi * (1.0 - std::cos(double(light.outerConeAngle))) * intensity;
  return 4.0 * kPi * intensity;
}

std::vector<gpu::GpuLightAlias> buildAliasTable(std::span<const double> weights) {
  const size_t n = weights.size();
  double sum = 0.0;
  for (double w : weights) {
    if (!(w >= 0.0) || !std::isfinite(w)) fail("alias table: weight {} is not finite and >= 0", w);
    sum += w;
  }
  if (!(sum > 0.0)) fail("alias table: the weights sum to {}", sum);

  std::vector<gpu::GpuLightAlias> table(n);
  std::vector<double> scaled(n);  // probability x n: 1 means "exactly its share"
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    table[i].pmf = float(weights[i] / sum);
    table[i].alias = uint32_t(i);
    scaled[i] = weights[i] / sum * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  // Each under-full entry is topped up by one over-full entry, which then may become under-full.
  while (!small.empty() && !large.empty()) {
    uint32_t s = small.back(), l = large.back();
    small.pop_back();
    table[s].threshold = float(scaled[s]);
    table[s].alias = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What remains is full up to rounding.
  for (uint32_t i : large) table[i].threshold = 1.0f;
  for (uint32_t i : small) table[i].threshold = 1.0f;
  return table;
}

LightTable buildLightTable(const Scene& scene, const rt::SceneBvh& bvh,
                           const std::vector<bool>& unsampledMaterials) {
  LightTable table;
  std::vector<float> materialLuminance;
  std::vector<glm::vec3> materialEmission;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    bool unsampled = m < unsampledMaterials.size() && unsampledMaterials[m];
    materialEmission.push_back(unsampled ? glm::vec3(0.0f)
                                         : meanEmission(scene, scene.materials[m]));
    materialLuminance.push_back(luminance(materialEmission.back()));
  }

  LocalLights emissive = gatherEmissiveTriangles(scene, bvh, materialEmission, materialLuminance);
  table.emissiveTriangleInstance = std::move(emissive.triangleInstance);
  table.materialEmissiveArea.assign(scene.materials.size(), 0.0);
  for (const gpu::GpuEmissiveTriangle& t : emissive.triangles)
    table.materialEmissiveArea[bvh.geometries.at(t.geometry).material] += t.area;
  table.emissiveTriangles = std::move(emissive.triangles);
  std::vector<double> power = std::move(emissive.trianglePower);
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLight& l = scene.lights[i];
    if (l.type == PunctualLight::Type::Directional) continue;
    // Switched off (power 0) too: the layout must not depend on the lights' state.
    table.punctualLights.push_back(makePunctualLight(l));
    table.punctualLightSource.push_back(i);
    power.push_back(std::max(punctualLightPower(l), 0.0));
  }
  table.distantLights = gatherDistantLights(scene);
  table.materialLuminance = std::move(materialLuminance);
  setLocalPower(table, power);
  return table;
}

void updateLightTable(LightTable& table, std::span<const PunctualLight> lights,
                      const rt::SceneBvh& bvh) {
  std::vector<double> power;
  power.reserve(table.localLightCount());
  for (size_t i = 0; i < table.emissiveTriangles.size(); ++i) {
    gpu::GpuEmissiveTriangle& t = table.emissiveTriangles[i];
    const uint32_t meanEmission = t.meanEmission;  // the material's: unchanged by a move
    t = placeEmissiveTriangle(bvh, bvh.instances.at(table.emissiveTriangleInstance[i]), t.geometry,
                              t.primitive);
    t.meanEmission = meanEmission;
    const float emitted = table.materialLuminance.at(bvh.geometries.at(t.geometry).material);
    power.push_back(kPi * double(t.area) * double(emitted));
  }
  for (size_t i = 0; i < table.punctualLights.size(); ++i) {
    const PunctualLight& l = lights[table.punctualLightSource.at(i)];
    table.punctualLights[i] = makePunctualLight(l);
    power.push_back(std::max(punctualLightPower(l), 0.0));
  }
  setLocalPower(table, power);
}

std::vector<uint32_t> buildEmissiveHitMap(const LightTable& table, const rt::SceneBvh& bvh) {
  std::vector<uint32_t> map(bvh.instances.size(), kNoLightEntry);
  for (size_t light = 0; light < table.emissiveTriangles.size(); ++light) {
    const gpu::GpuEmissiveTriangle& t = table.emissiveTriangles[light];
    const uint32_t instance = table.emissiveTriangleInstance[light];
    const gpu::GpuInstance& placed = bvh.instances[instance];
    if (map[instance] == kNoLightEntry) {
      // Geometry slots of this instance: one per geometry of its mesh.
      const size_t end = placed.mesh + 1 < bvh.geometryBase.size()
                             ? bvh.geometryBase[placed.mesh + 1]
                             : bvh.geometries.size();
      const uint32_t geometries = uint32_t(end - placed.geometryBase);
      map[instance] = uint32_t(map.size());
      map.resize(map.size() + geometries, kNoLightEntry);
    }
    const uint32_t geometrySlot = map[instance] + (t.geometry - placed.geometryBase);
    if (map.at(geometrySlot) == kNoLightEntry) {
      map[geometrySlot] = uint32_t(map.size());
      map.resize(map.size() + bvh.geometries.at(t.geometry).triangleCount, kNoLightEntry);
    }
    map.at(map[geometrySlot] + t.primitive) = uint32_t(light);
  }
  return map;
}

}  // namespace bounce
