// Foliage: a small forest of trees and bushes under an open sky. Leaves are alpha-tested cards
// (glTF MASK) cut out of a procedural leaf-sprig texture, so shadow and GI rays must alpha test;
// the canopy keeps most of the forest floor out of the sun, as in seed 000's benchmark scene.
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/procedural/random.h"

namespace bounce::procedural {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kLeafTextureSize = 256;
constexpr int kTreeGridSize = 6;      // trees per row and column
constexpr float kTreeSpacing = 6.0f;  // metres between tree rows
constexpr float kGroundHalfSize = 21.0f;
constexpr int kTreeVariants = 3;
constexpr int kBushVariants = 2;
constexpr int kBushCount = 18;

// ---- the leaf texture --------------------------------------------------------------------------

// One leaf of the sprig, in texture pixels.
struct LeafShape {
  glm::vec2 base;
  glm::vec2 direction;  // unit, base to tip
  float length;
  float width;
};

// Signed position of pixel p in the leaf's own frame: x along the midrib in [0, 1], y across in
// pixels. Inside when |y| is under the half-width profile, which tapers to points at both ends.
bool insideLeaf(const LeafShape& leaf, const glm::vec2& p, float& along, float& across) {
  glm::vec2 d = p - leaf.base;
  along = glm::dot(d, leaf.direction) / leaf.length;
  across = leaf.direction.x * d.y - leaf.direction.y * d.x;
  if (along < 0.0f || along > 1.0f) return false;
  float halfWidth = 0.5f * leaf.width * std::pow(std::sin(kPi * along), 0.75f);
  return std::abs(across) <= halfWidth;
}

// A sprig: a stem up the middle of the image with leaves alternating left and right and one at
// the tip. Alpha is exactly 0 or 255 so the MASK cutoff has no ambiguous texels; transparent
// texels keep the leaf colour so filtering at the edges does not darken the leaves.
Image makeLeafTexture() {
  const int n = kLeafTextureSize;
  const glm::vec2 stemBottom{0.5f * n, n - 4.0f};
  const glm::vec2 stemTop{0.5f * n, 0.2f * n};
  std::vector<LeafShape> leaves;
  Pcg32 rng(7);
  const int sideLeaves = 6;
  for (int i = 0; i < sideLeaves; ++i) {
    float along = 0.2f + 0.75f * float(i) / float(sideLeaves - 1);
    glm::vec2 base = glm::mix(stemBottom, stemTop, along);
    float side = (i % 2 == 0) ? -1.0f : 1.0f;
    float angle = glm::radians(rng.uniform(35.0f, 55.0f));
    glm::vec2 direction{side * std::sin(angle), -std::cos(angle)};
    leaves.push_back(
        {base, direction, rng.uniform(0.38f, 0.46f) * n, rng.uniform(0.19f, 0.23f) * n});
  }
  leaves.push_back({stemTop + glm::vec2(0, 6), {0, -1}, 0.2f * n, 0.14f * n});

  const glm::vec3 leafGreen{62, 118, 38};  // sRGB bytes
  const glm::vec3 veinGreen{44, 88, 28};
  const glm::vec3 stemColor{78, 84, 40};
  Image image;
  image.name = "leaf_sprig";
  image.width = image.height = n;
  image.rgba.resize(size_t(n) * n * 4);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      glm::vec2 p{x + 0.5f, y + 0.5f};
      glm::vec3 color = leafGreen;
      bool opaque = false;
      if (std::abs(p.x - stemBottom.x) <= 1.5f && p.y >= stemTop.y && p.y <= stemBottom.y) {
        color = stemColor;
        opaque = true;
      }
      for (const LeafShape& leaf : leaves) {
        float along, across;
        if (!insideLeaf(leaf, p, along, across)) continue;
        // Lighter towards the tip, darker along the midrib.
        color = std::abs(across) < 1.0f ? veinGreen : leafGreen * (0.9f + 0.25f * along);
        opaque = true;
      }
      uint8_t* texel = &image.rgba[(size_t(y) * n + x) * 4];
      for (int c = 0; c < 3; ++c) texel[c] = uint8_t(glm::clamp(color[c], 0.0f, 255.0f));
      texel[3] = opaque ? 255 : 0;
    }
  }
  return image;
}

// ---- trees and bushes --------------------------------------------------------------------------

struct FoliageMaterials {
  uint32_t ground, bark, leaf, bushLeaf;
};

FoliageMaterials addFoliageMaterials(Scene& scene, int leafTexture) {
  FoliageMaterials m;
  m.ground = addMaterial(scene, lambertMaterial("forest_floor", {0.28f, 0.24f, 0.14f}));
  m.bark = addMaterial(scene, lambertMaterial("bark", {0.30f, 0.22f, 0.15f}));
  auto leafMaterial = [&](const char* name, glm::vec3 tint) {
    Material leaf = lambertMaterial(name, tint);
    leaf.roughness = 0.6f;
    leaf.alphaMode = AlphaMode::Mask;
    leaf.alphaCutoff = 0.5f;
    leaf.doubleSided = true;
    leaf.baseColorTexture = leafTexture;
    return leaf;
  };
  m.leaf = addMaterial(scene, leafMaterial("leaf", glm::vec3(1.0f)));
  m.bushLeaf = addMaterial(scene, leafMaterial("bush_leaf", {0.80f, 0.95f, 0.60f}));
  return m;
}

glm::vec3 randomUnitVector(Pcg32& rng) {
  float z = rng.uniform(-1.0f, 1.0f);
  float phi = rng.uniform(0.0f, 2.0f * kPi);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 randomPointInEllipsoid(Pcg32& rng, const glm::vec3& center, const glm::vec3& radii) {
  for (;;) {
    glm::vec3 q{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
    if (glm::dot(q, q) <= 1.0f) return center + q * radii;
  }
}

// Leaf cards filling an ellipsoid crown. Cards lean towards facing up and out, the way leaves
// turn to the light, which is also what makes the canopy cast solid shade.
void addLeafCards(Geometry& g, Pcg32& rng, const glm::vec3& center, const glm::vec3& radii,
                  int count, float minSize, float maxSize) {
  for (int i = 0; i < count; ++i) {
    glm::vec3 c = randomPointInEllipsoid(rng, center, radii);
    // Cards stay whole above the ground (y = 0) rather than poking through it.
    c.y = std::max(c.y, 0.75f * maxSize);
    glm::vec3 outward = (c - center) / radii;
    glm::vec3 lean = 0.6f * outward + 0.6f * randomUnitVector(rng) + glm::vec3(0.0f, 0.5f, 0.0f);
    glm::vec3 normal = glm::length(lean) > 1e-3f ? glm::normalize(lean) : glm::vec3(0, 1, 0);
    glm::vec3 helper = std::abs(normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 u0 = glm::normalize(glm::cross(helper, normal));
    glm::vec3 v0 = glm::cross(normal, u0);
    float spin = rng.uniform(0.0f, 2.0f * kPi);
    glm::vec3 u = std::cos(spin) * u0 + std::sin(spin) * v0;  // card right
    glm::vec3 v = glm::cross(normal, u);                      // card up: cross(u, v) = normal
    float half = 0.5f * rng.uniform(minSize, maxSize);
    addQuad(g, c - half * u - half * v, c + half * u - half * v, c + half * u + half * v,
            c - half * u + half * v, glm::vec2(1.0f));
  }
}

Mesh makeTree(int variant, const FoliageMaterials& m) {
  Pcg32 rng(1000 + uint64_t(variant));
  MeshBuilder builder;
  Geometry& wood = builder.geometry(m.bark);
  const float height = rng.uniform(3.6f, 4.6f);
  const float radius = rng.uniform(0.20f, 0.28f);
  // The trunk starts below the ground so its bottom cap is buried, not coplanar with the ground.
  addFrustum(wood, {0, -0.2f, 0}, {0, height, 0}, radius, 0.55f * radius, 12, true);

  const glm::vec3 crownCenter{0.0f, height + 0.7f, 0.0f};
  const glm::vec3 crownRadii{rng.uniform(3.0f, 3.5f), rng.uniform(1.8f, 2.2f),
                             rng.uniform(3.0f, 3.5f)};
  const int branches = 5;
  for (int b = 0; b < branches; ++b) {
    float angle = 2.0f * kPi * (float(b) + rng.uniform(0.0f, 0.6f)) / float(branches);
    glm::vec3 start{0.0f, height * rng.uniform(0.65f, 0.9f), 0.0f};
    glm::vec3 end = crownCenter + 0.7f * glm::vec3(std::cos(angle) * crownRadii.x,
                                                   rng.uniform(-0.2f, 0.4f) * crownRadii.y,
                                                   std::sin(angle) * crownRadii.z);
    addFrustum(wood, start, end, 0.09f, 0.03f, 8, true);
  }
  addLeafCards(builder.geometry(m.leaf), rng, crownCenter, crownRadii, 340, 0.8f, 1.15f);
  return builder.build(fmt::format("tree_{}", variant));
}

Mesh makeBush(int variant, const FoliageMaterials& m) {
  Pcg32 rng(2000 + uint64_t(variant));
  MeshBuilder builder;
  const glm::vec3 radii{rng.uniform(0.9f, 1.3f), rng.uniform(0.6f, 0.8f), rng.uniform(0.9f, 1.3f)};
  addLeafCards(builder.geometry(m.bushLeaf), rng, {0.0f, 0.5f * radii.y, 0.0f}, radii, 70, 0.45f,
               0.7f);
  return builder.build(fmt::format("bush_{}", variant));
}

glm::mat4 placement(const glm::vec3& position, float yaw, float scale) {
  return translation(position) * rotationY(yaw) * glm::mat4(glm::mat3(scale));
}

Mesh makeGround(uint32_t material) {
  const float h = kGroundHalfSize;
  Frame ground{{-h, 0.0f, h}, {1, 0, 0}, {0, 0, -1}};
  MeshBuilder builder;
  addRect(builder.geometry(material), ground, {0, 0}, {2 * h, 2 * h});
  return builder.build("ground");
}

// Trees on a jittered grid centred on the origin; returns their trunk positions.
std::vector<glm::vec2> plantTrees(Scene& scene, uint32_t firstTreeMesh) {
  Pcg32 rng(31);
  std::vector<glm::vec2> trunks;
  const float start = -0.5f * kTreeSpacing * float(kTreeGridSize - 1);
  for (int row = 0; row < kTreeGridSize; ++row) {
    for (int col = 0; col < kTreeGridSize; ++col) {
      glm::vec2 p{start + kTreeSpacing * float(col) + rng.uniform(-1.0f, 1.0f),
                  start + kTreeSpacing * float(row) + rng.uniform(-1.0f, 1.0f)};
      uint32_t variant = uint32_t(rng.uniformInt(0, kTreeVariants - 1));
      float yaw = rng.uniform(0.0f, 2.0f * kPi);
      float scale = rng.uniform(0.9f, 1.15f);
      addInstance(scene, firstTreeMesh + variant, placement({p.x, 0.0f, p.y}, yaw, scale),
                  fmt::format("tree_r{}_c{}", row, col));
      trunks.push_back(p);
    }
  }
  return trunks;
}

// Bushes between the trees, kept clear of the trunks.
void plantBushes(Scene& scene, uint32_t firstBushMesh, const std::vector<glm::vec2>& trunks) {
  Pcg32 rng(47);
  const float extent = 0.5f * kTreeSpacing * float(kTreeGridSize);
  int planted = 0;
  while (planted < kBushCount) {
    glm::vec2 p{rng.uniform(-extent, extent), rng.uniform(-extent, extent)};
    bool clear = true;
    for (const glm::vec2& t : trunks) clear = clear && glm::distance(p, t) > 1.8f;
    if (!clear) continue;
    uint32_t variant = uint32_t(rng.uniformInt(0, kBushVariants - 1));
    addInstance(scene, firstBushMesh + variant,
                placement({p.x, 0.0f, p.y}, rng.uniform(0.0f, 2.0f * kPi), rng.uniform(0.8f, 1.2f)),
                fmt::format("bush_{}", planted));
    ++planted;
  }
}

}  // namespace

Scene makeFoliageScene() {
  Scene scene;
  scene.name = "foliage";
  scene.images.push_back(makeLeafTexture());
  const FoliageMaterials m = addFoliageMaterials(scene, 0);
  addMeshInstance(scene, makeGround(m.ground));

  const uint32_t firstTree = uint32_t(scene.meshes.size());
  for (int v = 0; v < kTreeVariants; ++v) addMesh(scene, makeTree(v, m));
  const uint32_t firstBush = uint32_t(scene.meshes.size());
  for (int v = 0; v < kBushVariants; ++v) addMesh(scene, makeBush(v, m));
  plantBushes(scene, firstBush, plantTrees(scene, firstTree));

  // Midday-ish sun; the canopy takes most of it, the sky fills the shade.
  scene.sun = sunFromAngles(55.0f, 35.0f, 100.0f, {1.0f, 0.94f, 0.84f});
  scene.sky.radiance = {1.4f, 2.0f, 3.0f};

  Camera camera;
  camera.position = {-13.0f, 1.7f, 11.0f};
  camera.target = {0.0f, 2.2f, -1.0f};
  camera.verticalFovDegrees = 60.0f;
  scene.camera = camera;
  return scene;
}

}  // namespace bounce::procedural
