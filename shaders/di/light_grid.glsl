// ReSTIR DI's world-space light grid (shared/di_light_grid_io.h; ReGIR, Boksansky et al. 2021,
// Ray Tracing Gems II ch. 23): the cell target di-light-grid resamples by, and how
// di-generate-candidates draws its light candidates from the grid and the alias table together.
//
// Candidates at a pixel: gridCandidates of the DiConstants::lightCandidates (M) come from the
// slots of the pixel's cell (a uniformly chosen slot: its light, with the slot's RIS weight W as
// the estimate of 1/pdf), the other Ma = M - gridCandidates from the alias table as before
// (sampleDiLight). That is generalised RIS (Lin et al. 2022, "Generalized resampled importance
// sampling", §4) over two techniques, each candidate weighted m_i(x) p_hat(x) W_i with MIS
// weights m that sum to 1 for every x:
//   - a light the cell can give (local, diCellTarget > 0): 1/M for every candidate;
//   - any other light (distant, or one the cell's target rules out): 0 for grid candidates
//     (they never give it) and 1/Ma for alias candidates.
// So the estimate stays unbiased whatever the cell's target misses (a jittered lookup's cell, a
// light the bound rules out wrongly): the alias candidates keep every light reachable, which is
// why a fraction of them stays (ReGIR's fallback). The grid's pdf is never evaluated: a slot's W
// is RIS's unbiased contribution weight, which is what generalised RIS needs.
#ifndef BOUNCE_DI_LIGHT_GRID_GLSL
#define BOUNCE_DI_LIGHT_GRID_GLSL
#include "di/di_common.glsl"
#include "shared/di_light_grid_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer DiLightGridBlock {
  DiLightGrid v;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer DiLightGridSlots {
  uvec2 v[];
};

const uint RANDOM_DI_LIGHT_GRID = 0x44490004u;

uint diLightGridCellCount(DiLightGrid g) { return g.cellsX * g.cellsY * g.cellsZ; }

// The grid's lowest corner this frame: the camera's cell in the middle, whole cells, so that a
// cell keeps its box while the camera stays in its own cell.
vec3 diLightGridOrigin(FrameConstants f, DiLightGrid g) {
  vec3 cameraCell = floor(f.camera.position / g.cellSize);
  return (cameraCell - vec3(uvec3(g.cellsX, g.cellsY, g.cellsZ) / 2u)) * g.cellSize;
}

// The cell holding x, or -1 outside the grid.
int diLightGridCell(DiLightGrid g, vec3 origin, vec3 x) {
  ivec3 c = ivec3(floor((x - origin) / g.cellSize));
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(uvec3(c), uvec3(g.cellsX, g.cellsY, g.cellsZ))))
    return -1;
  return int((uint(c.z) * g.cellsY + uint(c.y)) * g.cellsX + uint(c.x));
}

// The box of cell `cell`.
void diLightGridCellBox(DiLightGrid g, vec3 origin, uint cell, out vec3 lo, out vec3 hi) {
  uvec3 c = uvec3(cell % g.cellsX, (cell / g.cellsX) % g.cellsY, cell / (g.cellsX * g.cellsY));
  lo = origin + vec3(c) * g.cellSize;
  hi = lo + g.cellSize;
}

float diSquaredDistanceToBox(vec3 p, vec3 lo, vec3 hi) {
  vec3 d = max(max(lo - p, p - hi), vec3(0.0));
  return dot(d, d);
}

// The target of a cell (ReGIR's "contribution estimate to the cell", GI-1.0's
// sampleLightVolume): luminance of the light's intensity towards the box over the squared
// distance to the box, an upper bound of its unshadowed irradiance at any point of the box (no
// BRDF or cosine: the cell has no surface). 0 only where no point of the box can get light from
// it: a spot whose cone misses the box's bounding sphere, a triangle whose emitting side faces
// away from every corner. The distance is clamped below by half a cell so that a light inside
// the box does not take every slot.
float diCellTarget(uint light, vec3 lo, vec3 hi) {
  vec3 centre = 0.5 * (lo + hi);
  vec3 halfSize = 0.5 * (hi - lo);
  float minDistanceSq = dot(halfSize, halfSize) * (1.0 / 3.0);
  if (light >= lightTables.emissiveTriangleCount) {
    GpuPunctualLight p = loadPunctualLight(light - lightTables.emissiveTriangleCount);
    float attenuation = 1.0;
    vec3 toBox = centre - p.position;
    float distance = length(toBox);
    float radius = length(halfSize);
    if (p.type == PUNCTUAL_LIGHT_SPOT && distance > radius) {
      // The cosine of the smallest angle from the spot's axis to a point of the box's bounding
      // sphere: 1 where the axis passes through the sphere's cone (axis angle A at most the
      // sphere's angular radius B), else cos(A - B) = cos A cos B + sin A sin B, which needs no
      // inverse trigonometry (every pixel evaluates this for each of its candidates).
      float cosA = clamp(dot(p.spotDirection, toBox / distance), -1.0, 1.0);
      float sinB = radius / distance;
      float cosB = sqrt(max(1.0 - sinB * sinB, 0.0));
      float cosNearest = cosA >= cosB ? 1.0 : cosA * cosB + sqrt(max(1.0 - cosA * cosA, 0.0)) * sinB;
      float a = clamp(cosNearest * p.angleScale + p.angleOffset, 0.0, 1.0);
      attenuation = a * a;
    }
    float distanceSq = max(diSquaredDistanceToBox(p.position, lo, hi), minDistanceSq);
    return brdfLuminance(p.intensity) * attenuation / distanceSq;
  }
  GpuEmissiveTriangle e = loadEmissiveTriangle(light);
  // Emits towards the box when its front side faces at least one corner.
  if (dot(e.frontNormal, centre - e.p0) + dot(abs(e.frontNormal), halfSize) <= 0.0) return 0.0;
  vec3 triangleCentre = e.p0 + (e.edge1 + e.edge2) * (1.0 / 3.0);
  float triangleRadius = sqrt(max(dot(e.p0 - triangleCentre, e.p0 - triangleCentre),
                                  max(dot(e.p0 + e.edge1 - triangleCentre, e.p0 + e.edge1 - triangleCentre),
                                      dot(e.p0 + e.edge2 - triangleCentre, e.p0 + e.edge2 - triangleCentre))));
  float distance = max(sqrt(diSquaredDistanceToBox(triangleCentre, lo, hi)) - triangleRadius, 0.0);
  return brdfLuminance(decodeRgb9e5(e.meanEmission)) * e.area / max(distance * distance, minDistanceSq);
}

// ---- candidates at a pixel --------------------------------------------------------------------

// The grid as one pixel's candidates see it: its cell (or none) and how the M candidates split.
struct DiGridLookup {
  DiLightGrid grid;
  int cell;            // -1: no grid, or the point is outside it
  vec3 lo, hi;         // the cell's box
  uint gridCount;      // candidates from the grid (0 without a cell)
  float count;         // M
};

// The cell of x, its lookup jittered by up to half a cell on each axis (ReGIR's jitter, which
// hides the cells' edges; the MIS weights above keep any cell unbiased).
DiGridLookup diLightGridLookup(FrameConstants f, DiConstants di, vec3 x, vec3 jitter) {
  DiGridLookup q;
  q.count = float(di.lightCandidates);
  q.cell = -1;
  q.gridCount = 0u;
  q.lo = q.hi = vec3(0.0);
  if (di.lightGrid == 0ul) return q;
  q.grid = DiLightGridBlock(di.lightGrid).v;
  vec3 origin = diLightGridOrigin(f, q.grid);
  q.cell = diLightGridCell(q.grid, origin, x + (jitter - 0.5) * q.grid.cellSize);
  if (q.cell < 0) return q;
  diLightGridCellBox(q.grid, origin, uint(q.cell), q.lo, q.hi);
  // At least one alias candidate: the one technique that reaches every light.
  q.gridCount = min(q.grid.gridCandidates, di.lightCandidates - 1u);
  return q;
}

// Candidate i of the pixel: its light (DI_NO_LIGHT: none), u (quantised as the reservoir stores
// it), and `sourceWeight` = m_i(x) W_i (the MIS weight above times the candidate's unbiased
// contribution weight), so that its RIS weight is p_hat(x) sourceWeight. a, b: uniform numbers.
uint diSampleLightCandidate(DiGridLookup q, uint i, vec4 a, vec2 b, out vec2 u, out float sourceWeight) {
  sourceWeight = 0.0;
  if (i < q.gridCount) {
    u = unpackUnorm2x16(packUnorm2x16(b));
    uint slot = min(uint(a.x * float(q.grid.slotsPerCell)), q.grid.slotsPerCell - 1u);
    uvec2 entry = DiLightGridSlots(q.grid.slots).v[uint(q.cell) * q.grid.slotsPerCell + slot];
    float W = uintBitsToFloat(entry.y);
    // The cell's target is evaluated here again, not trusted from the build: the MIS weights
    // must partition unity with this evaluation's zeros, whatever the compilers round.
    if (entry.x >= lightTables.localLightCount || !(W > 0.0) || !(diCellTarget(entry.x, q.lo, q.hi) > 0.0))
      return DI_NO_LIGHT;
    sourceWeight = W / q.count;
    return entry.x;
  }
  float pdf;
  uint light = sampleDiLight(a, b, u, pdf);
  if (light == DI_NO_LIGHT || !(pdf > 0.0)) return DI_NO_LIGHT;
  bool gridGives = q.gridCount > 0u && (light & DI_LIGHT_DISTANT) == 0u && diCellTarget(light, q.lo, q.hi) > 0.0;
  float m = gridGives ? 1.0 / q.count : 1.0 / (q.count - float(q.gridCount));
  sourceWeight = m / pdf;
  return light;
}

#endif
