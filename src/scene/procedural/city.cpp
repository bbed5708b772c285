// The city: an 8 x 8 grid of blocks of buildings for BVH and traversal stress. Facades are
// real geometry (every window is a hole with a recessed pane and reveals; floors have ledges),
// so triangles are many, small and axis-aligned, with long thin slivers: hard cases for SAH.
// A few dozen unique block designs (about 400k triangles) are instanced, rotated, over the
// grid, and streets get instanced street lights and cars: over 1.5M triangles as rays see them.
//
// Every street light is a real light (16 to a block, 1,024 in all): an emissive lamp cover
// and a KHR spot light shining down just under it, so the city by night (--time-of-day 22) is
// lit by its streets (docs/di.md). `city-10k` is the same city on a 25 x 25 grid: the same
// unique meshes, 10,000 street lights, for the many-lights scale test.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <fmt/format.h>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/procedural/random.h"

namespace bounce::procedural {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kBlockDesigns = 18;
constexpr float kBlockSize = 64.0f;
constexpr float kStreetWidth = 16.0f;
constexpr float kBlockPitch = kBlockSize + kStreetWidth;
constexpr float kSidewalkWidth = 3.0f;
constexpr float kSidewalkHeight = 0.15f;

// The grid's size: blocks along each axis, and the half size to the outer street's middle.
struct CityGrid {
  int blocksPerSide;
  float halfSize() const { return 0.5f * kBlockPitch * float(blocksPerSide); }
  // The centre of block (bx, bz) on the ground.
  glm::vec3 blockCenter(int bx, int bz) const {
    const float middle = 0.5f * float(blocksPerSide - 1);
    return {(float(bx) - middle) * kBlockPitch, 0.0f, (float(bz) - middle) * kBlockPitch};
  }
};

// ---- street lamps ------------------------------------------------------------------------------
//
// Photometry. The scene's units are its sun's: sunFromAngles(..., 100) is a clear day's
// kDaylightSunKilolux = 100 klux (scene.h), so irradiance 1 = 1 klux, a punctual intensity of
// 1 = 1 kcd (the renderer reads intensity as W/sr in the sun's units, lighting_io.h) and
// radiance 1 = 1 kcd/m^2. One lamp is a 100 W LED street luminaire at 120 lm/W: 12,000 lm
// leave it, about what a 150 W high-pressure sodium lamp gives after its luminaire's losses.
// Its light is warm white, 3000 K. A fifth of the flux leaves through the lamp cover as a
// Lambertian glow (what the camera and glossy surfaces see), the rest is the LED array's beam:
// a spot light pointing down with a wide cut-off (full intensity to 55 degrees from the nadir,
// none beyond 75), as street optics spread light along the road and keep it out of windows.
// Under a lamp (7 m up) the street gets about 60 lux from the beam and 15 from the cover;
// road-lighting classes ask for 10-30 lux on average (EN 13201-2).
constexpr float kLampFluxKilolumens = 12.0f;
constexpr float kLampCoverShare = 0.2f;
constexpr float kLampBeamInnerDegrees = 55.0f;
constexpr float kLampBeamOuterDegrees = 75.0f;
// A 3000 K blackbody in linear Rec. 709, scaled to a maximum of 1 (Planck's law integrated
// against the CIE 1931 observer, in the analytic fit of Wyman, Sloan & Shirley 2013, "Simple
// Analytic Approximations to the CIE XYZ Color Matching Functions"); its luminance is 0.570.
constexpr glm::vec3 kLampColor{1.0f, 0.484f, 0.155f};
// The street light's lamp head (in the street light mesh's frame, arm along +X); the cover closes
// its underside (0.21 m^2), and the beam starts 2 cm under the cover's middle, so the cover
// does not shadow it.
const Aabb kLampHead{{1.35f, 6.95f, -0.15f}, {2.05f, 7.1f, 0.15f}};
const glm::vec3 kLampBeamOrigin{1.7f, 6.93f, 0.0f};

float luminanceOf(const glm::vec3& rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

// The cover's emitted radiance (RGB, kcd/m^2 in luminance): a Lambertian emitter of area A
// sends pi A L, so L = flux / (pi A).
glm::vec3 lampCoverEmission() {
  const glm::vec3 size = kLampHead.max - kLampHead.min;
  const float luminance = kLampCoverShare * kLampFluxKilolumens / (kPi * size.x * size.z);
  return kLampColor * (luminance / luminanceOf(kLampColor));
}

// The solid angle the glTF spot falloff a(theta) = clamp((cos theta - cos o) / (cos i - cos o),
// 0, 1)^2 integrates to: 2 pi (integral over cos theta of a) = 2 pi ((1 - cos i) +
// (cos i - cos o) / 3). The beam's intensity is its flux over this.
float spotEffectiveSolidAngle(float innerRadians, float outerRadians) {
  const float cosInner = std::cos(innerRadians), cosOuter = std::cos(outerRadians);
  return 2.0f * kPi * ((1.0f - cosInner) + (cosInner - cosOuter) / 3.0f);
}

// The spot light of one lamp at `position`, shining straight down.
PunctualLight lampBeam(const glm::vec3& position, std::string name) {
  PunctualLight light;
  light.type = PunctualLight::Type::Spot;
  light.name = std::move(name);
  light.color = kLampColor;
  light.innerConeAngle = kLampBeamInnerDegrees * kPi / 180.0f;
  light.outerConeAngle = kLampBeamOuterDegrees * kPi / 180.0f;
  const float candela = (1.0f - kLampCoverShare) * kLampFluxKilolumens /
                        spotEffectiveSolidAngle(light.innerConeAngle, light.outerConeAngle);
  light.intensity = candela / luminanceOf(kLampColor);
  light.position = position;
  light.direction = {0.0f, -1.0f, 0.0f};
  return light;
}

struct CityMaterials {
  std::vector<uint32_t> facades;
  uint32_t glass, roof, sidewalk, asphalt, poleMetal, lampGlass, tyre;
  std::vector<uint32_t> carPaints;
};

CityMaterials addCityMaterials(Scene& scene) {
  CityMaterials m;
  const std::pair<const char*, glm::vec3> facades[] = {
      {"facade_concrete", {0.60f, 0.58f, 0.55f}},  {"facade_brick", {0.55f, 0.30f, 0.22f}},
      {"facade_sandstone", {0.75f, 0.65f, 0.50f}}, {"facade_white", {0.80f, 0.80f, 0.78f}},
      {"facade_dark", {0.25f, 0.26f, 0.28f}},      {"facade_teal", {0.35f, 0.50f, 0.50f}},
  };
  for (const auto& [name, color] : facades)
    m.facades.push_back(addMaterial(scene, lambertMaterial(name, color)));
  auto glossy = [](const char* name, glm::vec3 color, float metallic, float roughness) {
    Material mat = lambertMaterial(name, color);
    mat.metallic = metallic;
    mat.roughness = roughness;
    return mat;
  };
  m.glass = addMaterial(scene, glossy("window_glass", {0.05f, 0.07f, 0.09f}, 0.0f, 0.05f));
  m.roof = addMaterial(scene, lambertMaterial("roof_tar", {0.20f, 0.20f, 0.21f}));
  m.sidewalk = addMaterial(scene, lambertMaterial("sidewalk_concrete", {0.55f, 0.55f, 0.52f}));
  m.asphalt = addMaterial(scene, lambertMaterial("street_asphalt", {0.08f, 0.08f, 0.09f}));
  m.poleMetal = addMaterial(scene, glossy("street_light_metal", {0.15f, 0.16f, 0.17f}, 1.0f, 0.4f));
  Material cover = glossy("street_light_cover", {0.90f, 0.90f, 0.85f}, 0.0f, 0.2f);
  cover.emissive = lampCoverEmission();
  m.lampGlass = addMaterial(scene, cover);
  m.tyre = addMaterial(scene, lambertMaterial("tyre_rubber", {0.03f, 0.03f, 0.03f}));
  const std::pair<const char*, glm::vec3> paints[] = {
      {"car_paint_red", {0.60f, 0.05f, 0.04f}},
      {"car_paint_silver", {0.55f, 0.56f, 0.58f}},
      {"car_paint_blue", {0.05f, 0.12f, 0.40f}},
  };
  for (const auto& [name, color] : paints)
    m.carPaints.push_back(addMaterial(scene, glossy(name, color, 0.0f, 0.3f)));
  return m;
}

// ---- buildings ---------------------------------------------------------------------------------

// How one building's facades look.
struct FacadeStyle {
  float floorHeight;
  float bayWidth;    // target width of one window bay; facades round it to fit
  glm::vec2 window;  // window size as fractions of the bay width and the floor height
  float sill;        // fraction of the floor height below the window
  float insetDepth;  // how far the glass sits behind the wall
  bool ledges;       // a protruding band at every floor line
  uint32_t wall;
  uint32_t glass;
};

FacadeStyle randomFacadeStyle(Pcg32& rng, const CityMaterials& m) {
  FacadeStyle s;
  s.floorHeight = rng.uniform(3.0f, 3.6f);
  s.bayWidth = rng.uniform(2.4f, 3.6f);
  s.window = {rng.uniform(0.45f, 0.75f), rng.uniform(0.42f, 0.62f)};
  s.sill = rng.uniform(0.22f, 0.30f);
  s.insetDepth = rng.uniform(0.12f, 0.3f);
  s.ledges = rng.uniform() < 0.5f;
  s.wall = m.facades[size_t(rng.uniformInt(0, int(m.facades.size()) - 1))];
  s.glass = m.glass;
  return s;
}

// One facade of `floors` floors: a grid of window bays, each a wall with a hole, the hole's
// reveals and a recessed pane; optionally a ledge at every floor line, running past both
// corners so neighbouring facades' ledges meet.
void addFacade(MeshBuilder& builder, const Frame& frame, float width, int floors,
               const FacadeStyle& style) {
  Geometry& wall = builder.geometry(style.wall);
  Geometry& glass = builder.geometry(style.glass);
  const int bays = std::max(1, int(std::lround(width / style.bayWidth)));
  const Frame pane{frame.point(0, 0, style.insetDepth), frame.right, frame.up};
  // Bay edges from one expression, so neighbouring bays share them exactly; the last one is the
  // facade's end itself, where the next facade starts.
  auto bayEdge = [&](int bay) { return bay == bays ? width : width * float(bay) / float(bays); };
  for (int floor = 0; floor < floors; ++floor) {
    const float t0 = float(floor) * style.floorHeight;
    const float t1 = float(floor + 1) * style.floorHeight;
    for (int bay = 0; bay < bays; ++bay) {
      const float s0 = bayEdge(bay);
      const float s1 = bayEdge(bay + 1);
      const float margin = 0.5f * (1.0f - style.window.x) * (s1 - s0);
      const glm::vec2 holeMin{s0 + margin, t0 + style.sill * style.floorHeight};
      const glm::vec2 holeMax{s1 - margin, holeMin.y + style.window.y * style.floorHeight};
      addRectWithHole(wall, frame, {s0, t0}, {s1, t1}, holeMin, holeMax);
      addOpeningSides(wall, frame, holeMin, holeMax, style.insetDepth);
      addRect(glass, pane, holeMin, holeMax);
    }
    if (style.ledges && floor > 0) {
      const float out = 0.18f, halfHeight = 0.1f;
      glm::vec3 corners[8];
      for (int i = 0; i < 8; ++i)
        corners[i] = frame.point(i & 1 ? width + out : -out,
                                 t0 + (i & 2 ? halfHeight : -halfHeight), i & 4 ? -out : 0.0f);
      // Bit 2 = 0 is the face against the wall, never seen.
      addHexahedron(wall, corners, Facing::Outward, kAllFaces & ~kFaceNegZ);
    }
  }
}

// A box-shaped building part of `floors` floors standing at height `base`, its four facades
// facing out of `footprint` (x, z extents in xy of the vec4: x0, z0, x1, z1).
void addTier(MeshBuilder& builder, const glm::vec4& footprint, float base, int floors,
             const FacadeStyle& style, uint32_t roofMaterial) {
  const float x0 = footprint.x, z0 = footprint.y, x1 = footprint.z, z1 = footprint.w;
  const glm::vec3 up{0, 1, 0};
  addFacade(builder, Frame{{x0, base, z1}, {1, 0, 0}, up}, x1 - x0, floors, style);   // faces +Z
  addFacade(builder, Frame{{x1, base, z1}, {0, 0, -1}, up}, z1 - z0, floors, style);  // faces +X
  addFacade(builder, Frame{{x1, base, z0}, {-1, 0, 0}, up}, x1 - x0, floors, style);  // faces -Z
  addFacade(builder, Frame{{x0, base, z0}, {0, 0, 1}, up}, z1 - z0, floors, style);   // faces -X
  const float top = base + float(floors) * style.floorHeight;
  addRect(builder.geometry(roofMaterial), Frame{{x0, top, z1}, {1, 0, 0}, {0, 0, -1}}, {0, 0},
          {x1 - x0, z1 - z0});
}

// Footprint corners on a 1/64 m grid: then x0 + (x1 - x0) == x1 exactly in float, so the
// facades, which run from one corner by their width, end exactly where the next one starts.
glm::vec4 snapToGrid(const glm::vec4& v) {
  return glm::round(v * 64.0f) / 64.0f;
}

// A building on a lot: setback from the lot edges, a random height skewed towards low-rise,
// tall ones stepping back into a narrower tower, and a few boxes on the roof.
void addBuilding(MeshBuilder& builder, Pcg32& rng, const glm::vec4& lot, const CityMaterials& m) {
  const FacadeStyle style = randomFacadeStyle(rng, m);
  glm::vec4 footprint =
      snapToGrid(lot + glm::vec4(rng.uniform(0.0f, 2.5f), rng.uniform(0.0f, 2.5f),
                                 -rng.uniform(0.0f, 2.5f), -rng.uniform(0.0f, 2.5f)));
  const float u = rng.uniform();
  const int floors = 3 + int(22.0f * u * u);
  int lowerFloors = floors;
  if (floors > 12 && rng.uniform() < 0.6f) lowerFloors = int(0.6f * float(floors));
  const float base = kSidewalkHeight;
  addTier(builder, footprint, base, lowerFloors, style, m.roof);
  float top = base + float(lowerFloors) * style.floorHeight;
  if (lowerFloors < floors) {
    const float setback = snapToGrid(glm::vec4(rng.uniform(2.0f, 4.0f))).x;
    footprint += glm::vec4(setback, setback, -setback, -setback);
    addTier(builder, footprint, top, floors - lowerFloors, style, m.roof);
    top += float(floors - lowerFloors) * style.floorHeight;
  }
  const int roofBoxes = rng.uniformInt(1, 2);
  for (int i = 0; i < roofBoxes; ++i) {
    glm::vec2 room{footprint.z - footprint.x - 1.0f, footprint.w - footprint.y - 1.0f};
    glm::vec2 size = glm::min(glm::vec2(rng.uniform(2.0f, 5.0f), rng.uniform(2.0f, 5.0f)), room);
    glm::vec2 c{
        rng.uniform(footprint.x + 0.5f * size.x + 0.5f, footprint.z - 0.5f * size.x - 0.5f),
        rng.uniform(footprint.y + 0.5f * size.y + 0.5f, footprint.w - 0.5f * size.y - 0.5f)};
    addBox(builder.geometry(m.roof),
           Aabb{{c.x - 0.5f * size.x, top, c.y - 0.5f * size.y},
                {c.x + 0.5f * size.x, top + rng.uniform(1.5f, 3.0f), c.y + 0.5f * size.y}},
           Facing::Outward, kNoBottom);
  }
}

// Splits the buildable square of a block into 1, 2, 3 or 4 lots (x0, z0, x1, z1) with alleys.
std::vector<glm::vec4> splitIntoLots(Pcg32& rng) {
  const float h = 0.5f * kBlockSize - kSidewalkWidth;
  const float alley = 2.0f;
  switch (rng.uniformInt(0, 3)) {
    case 0:
      return {{-h, -h, h, h}};
    case 1: {
      float cut = rng.uniform(-0.3f, 0.3f) * h;
      return {{-h, -h, cut - 0.5f * alley, h}, {cut + 0.5f * alley, -h, h, h}};
    }
    case 2: {
      float a = -h / 3.0f, b = h / 3.0f;
      return {{-h, -h, a - 0.5f * alley, h},
              {a + 0.5f * alley, -h, b - 0.5f * alley, h},
              {b + 0.5f * alley, -h, h, h}};
    }
    default: {
      float cx = rng.uniform(-0.2f, 0.2f) * h, cz = rng.uniform(-0.2f, 0.2f) * h, a = 0.5f * alley;
      return {{-h, -h, cx - a, cz - a},
              {cx + a, -h, h, cz - a},
              {-h, cz + a, cx - a, h},
              {cx + a, cz + a, h, h}};
    }
  }
}

// One block design centred on the origin: a sidewalk slab and its buildings.
Mesh makeBlockDesign(int design, const CityMaterials& m) {
  Pcg32 rng(5000 + uint64_t(design));
  MeshBuilder builder;
  const float h = 0.5f * kBlockSize;
  addBox(builder.geometry(m.sidewalk), Aabb{{-h, 0.0f, -h}, {h, kSidewalkHeight, h}},
         Facing::Outward, kNoBottom);
  for (const glm::vec4& lot : splitIntoLots(rng)) addBuilding(builder, rng, lot, m);
  return builder.build(fmt::format("block_design_{}", design));
}

// ---- street props ------------------------------------------------------------------------------

// A street light standing at the origin, its arm reaching over the street along +X.
Mesh makeStreetLight(const CityMaterials& m) {
  MeshBuilder builder;
  Geometry& metal = builder.geometry(m.poleMetal);
  // Parts overlap a little (base into the sidewalk, pole into the base, arm into pole and head)
  // so no cap lies in another part's face plane.
  addFrustum(metal, {0, -0.05f, 0}, {0, 0.5f, 0}, 0.18f, 0.12f, 16);
  addFrustum(metal, {0, 0.45f, 0}, {0, 7.0f, 0}, 0.10f, 0.06f, 16);
  addCylinder(metal, {0, 6.75f, 0}, {1.6f, 7.05f, 0}, 0.04f, 12);
  const Aabb& head = kLampHead;
  addBox(metal, head, Facing::Outward, kAllFaces & ~kFaceNegY);
  // The lamp cover closes the head's underside.
  addBox(builder.geometry(m.lampGlass), head, Facing::Outward, kFaceNegY);
  return builder.build("street_light");
}

// A car as boxes and wheels, 4.3 m long along +X, standing at the origin.
Mesh makeCar(uint32_t paint, const CityMaterials& m, int variant) {
  MeshBuilder builder;
  addBox(builder.geometry(paint), Aabb{{-2.15f, 0.3f, -0.88f}, {2.15f, 0.95f, 0.88f}});
  // The cabin tapers towards the roof: a hexahedron, corners indexed x | y << 1 | z << 2.
  glm::vec3 cabin[8];
  for (int i = 0; i < 8; ++i) {
    bool high = i & 2;
    float x = (i & 1) ? (high ? 0.45f : 1.0f) : (high ? -0.95f : -1.25f);
    float z = (i & 4) ? (high ? 0.72f : 0.84f) : (high ? -0.72f : -0.84f);
    cabin[i] = {x, high ? 1.45f : 0.95f, z};
  }
  addHexahedron(builder.geometry(m.glass), cabin, Facing::Outward, kAllFaces & ~kFaceNegY);
  for (float x : {-1.35f, 1.35f})
    for (float z : {-0.78f, 0.78f}) {
      float outer = z > 0 ? 0.11f : -0.11f;
      addCylinder(builder.geometry(m.tyre), {x, 0.33f, z - outer}, {x, 0.33f, z + outer}, 0.33f,
                  16);
    }
  return builder.build(fmt::format("car_{}", variant));
}

// Street lights along each block's sidewalk, four to a side, arms over the street; each one's
// lamp gets its beam (the cover emits through its material).
void placeStreetLights(Scene& scene, uint32_t mesh, const CityGrid& grid) {
  const float edge = 0.5f * kBlockSize - 0.8f;
  int count = 0;
  for (int bx = 0; bx < grid.blocksPerSide; ++bx)
    for (int bz = 0; bz < grid.blocksPerSide; ++bz) {
      const glm::vec3 center = grid.blockCenter(bx, bz) + glm::vec3(0.0f, kSidewalkHeight, 0.0f);
      for (int side = 0; side < 4; ++side) {
        // Side k faces along the rotated +X; the light's arm points the same way, over the street.
        float yaw = float(side) * 0.5f * kPi;
        for (float along : {-24.0f, -8.0f, 8.0f, 24.0f}) {
          const glm::mat4 transform =
              translation(center) * rotationY(yaw) * translation({edge, 0.0f, along});
          const std::string name = fmt::format("street_light_{}", count++);
          scene.lights.push_back(
              lampBeam(glm::vec3(transform * glm::vec4(kLampBeamOrigin, 1.0f)), name + "_beam"));
          addInstance(scene, mesh, transform, name);
        }
      }
    }
}

// Cars parked or driving in both lanes of every street, right-hand traffic, clear of crossings.
void placeCars(Scene& scene, uint32_t firstCarMesh, int variants, const CityGrid& grid) {
  const float halfSize = grid.halfSize();
  Pcg32 rng(77);
  int count = 0;
  for (int axis = 0; axis < 2; ++axis)
    for (int line = 0; line <= grid.blocksPerSide; ++line) {
      const float street = -halfSize + float(line) * kBlockPitch;
      for (int lane = 0; lane < 2; ++lane) {
        const float direction = lane == 0 ? 1.0f : -1.0f;
        const float offset = direction * 0.25f * kStreetWidth;
        for (float pos = -halfSize + rng.uniform(5.0f, 30.0f); pos < halfSize;
             pos += rng.uniform(9.0f, 45.0f)) {
          // Distance to the nearest crossing's middle; cars keep out of crossings.
          float fromCrossing = std::abs(std::remainder(pos + halfSize, kBlockPitch));
          if (fromCrossing < 0.5f * kStreetWidth + 2.5f) continue;
          glm::vec3 p = axis == 0 ? glm::vec3(pos, 0.0f, street + offset)
                                  : glm::vec3(street - offset, 0.0f, pos);
          // The car's +X runs along the street in its lane's direction.
          float yaw =
              axis == 0 ? (direction > 0 ? 0.0f : kPi) : (direction > 0 ? -0.5f * kPi : 0.5f * kPi);
          uint32_t mesh = firstCarMesh + uint32_t(rng.uniformInt(0, variants - 1));
          addInstance(scene, mesh, translation(p) * rotationY(yaw), fmt::format("car_{}", count++));
        }
      }
    }
}

Mesh makeGround(uint32_t asphalt, const CityGrid& grid) {
  const float h = grid.halfSize() + 40.0f;
  MeshBuilder builder;
  addRect(builder.geometry(asphalt), Frame{{-h, 0.0f, h}, {1, 0, 0}, {0, 0, -1}}, {0, 0},
          {2 * h, 2 * h});
  return builder.build("ground");
}

// Blocks get designs in a shuffled order so each design appears, and rotations in quarter turns
// so repeats are less obvious.
void placeBlocks(Scene& scene, uint32_t firstDesignMesh, const CityGrid& grid) {
  const int n = grid.blocksPerSide;
  Pcg32 rng(99);
  std::vector<int> order(size_t(n * n));
  std::iota(order.begin(), order.end(), 0);
  for (size_t i = order.size() - 1; i > 0; --i)
    std::swap(order[i], order[size_t(rng.nextUint() % (i + 1))]);
  for (int bx = 0; bx < n; ++bx)
    for (int bz = 0; bz < n; ++bz) {
      int design = order[size_t(bx * n + bz)] % kBlockDesigns;
      const glm::vec3 center = grid.blockCenter(bx, bz);
      float yaw = float(rng.uniformInt(0, 3)) * 0.5f * kPi;
      addInstance(scene, firstDesignMesh + uint32_t(design), translation(center) * rotationY(yaw),
                  fmt::format("block_{}_{}", bx, bz));
    }
}

// The default motion (--animate): the camera drives 24 m down the avenue and back over 8 s
// (0.2 m a frame at 30 frames a second), drifting 1.5 m to either side, its view direction
// kept. Not the built-in sway around the point looked at, which for a target 590 m away swings
// the camera through the facades beside the avenue.
CameraPath avenueDrive(const Camera& camera) {
  CameraPath path;
  path.loop = true;
  const glm::vec3 view = camera.target - camera.position;
  const glm::vec3 ahead = glm::normalize(glm::vec3(view.x, 0.0f, view.z));
  const glm::vec3 side = glm::cross(ahead, glm::vec3(0.0f, 1.0f, 0.0f));
  const float along[] = {0.0f, 12.0f, 24.0f, 12.0f, 0.0f};
  const float across[] = {0.0f, 1.5f, 0.0f, -1.5f, 0.0f};
  for (int i = 0; i < 5; ++i) {
    CameraKeyframe k;
    k.time = 2.0f * float(i);
    k.position = camera.position + along[i] * ahead + across[i] * side;
    k.target = k.position + view;
    k.verticalFovDegrees = camera.verticalFovDegrees;
    path.keys.push_back(k);
  }
  return path;
}

// The city on a grid of `blocksPerSide` blocks, its camera looking down the avenue nearest to
// x = 0 (a street runs there when the count is even; else one runs half a block east).
Scene makeCity(const CityGrid& grid) {
  Scene scene;
  scene.name = "city";
  const CityMaterials m = addCityMaterials(scene);
  addMeshInstance(scene, makeGround(m.asphalt, grid));

  const uint32_t firstDesign = uint32_t(scene.meshes.size());
  for (int d = 0; d < kBlockDesigns; ++d) addMesh(scene, makeBlockDesign(d, m));
  placeBlocks(scene, firstDesign, grid);

  placeStreetLights(scene, addMesh(scene, makeStreetLight(m)), grid);
  const uint32_t firstCar = uint32_t(scene.meshes.size());
  for (size_t v = 0; v < m.carPaints.size(); ++v)
    addMesh(scene, makeCar(m.carPaints[v], m, int(v)));
  placeCars(scene, firstCar, int(m.carPaints.size()), grid);

  scene.sun = sunFromAngles(35.0f, 60.0f, 100.0f, {1.0f, 0.95f, 0.88f});
  scene.sky.radiance = {1.4f, 2.0f, 3.0f};

  // Slightly above the street, looking down the avenue towards -Z.
  const float avenue = grid.blocksPerSide % 2 == 0 ? 0.0f : 0.5f * kBlockPitch;
  Camera camera;
  camera.position = {avenue + 2.5f, 6.0f, 290.0f};
  camera.target = {avenue - 1.0f, 14.0f, -300.0f};
  camera.verticalFovDegrees = 55.0f;
  scene.camera = camera;
  scene.animation.camera = avenueDrive(camera);
  return scene;
}

}  // namespace

Scene makeCityScene() {
  return makeCity(CityGrid{kCityBlocksPerSide});
}

Scene makeCity10kScene() {
  Scene scene = makeCity(CityGrid{kCity10kBlocksPerSide});
  scene.name = "city-10k";
  return scene;
}

}  // namespace bounce::procedural
