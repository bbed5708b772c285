// di-light-grid: every slot of the world-space light grid (shared/di_light_grid_io.h) gets one
// local light by RIS (Talbot 2005) over DiLightGrid::buildCandidates alias-table candidates
// (drawn by power, pmf p) with the cell's target diCellTarget (light_grid.glsl): candidate x_j
// weighs p_hat(x_j) / (B p(x_j)), the kept one x has W = (sum of weights) / p_hat(x), RIS's
// unbiased contribution weight, which di-generate-candidates uses as 1/pdf of the slot's light.
// One thread per slot; slots are independent (fresh random numbers each frame), rebuilt every
// frame for the camera-centred grid of this frame.
#version 460
#include "di/light_grid.glsl"

layout(local_size_x = DI_LIGHT_GRID_GROUP_SIZE) in;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  DiLightGrid g = DiLightGridBlock(di.lightGrid).v;
  uint slot = gl_GlobalInvocationID.x;
  uint cell = slot / g.slotsPerCell;
  if (cell >= diLightGridCellCount(g)) return;
  lightTables = LightTablesBlock(di.lights).v;
  vec3 lo, hi;
  diLightGridCellBox(g, diLightGridOrigin(f, g), cell, lo, hi);
  uvec4 key = pcg4d(uvec4(slot, f.frameIndex, RANDOM_DI_LIGHT_GRID, di.seed * 0x9E3779B9u));
  uint kept = DI_NO_LIGHT;
  float weightSum = 0.0, keptTarget = 0.0;
  float count = float(g.buildCandidates);
  [[dont_unroll]] for (uint i = 0u; i < g.buildCandidates; ++i) {
    vec4 u = diRandom(key);
    float pmf;
    uint light = pickLocalLight(u.xy, pmf);
    float target = pmf > 0.0 ? diCellTarget(light, lo, hi) : 0.0;
    float w = target > 0.0 ? target / (count * pmf) : 0.0;
    if (!(w > 0.0)) continue;
    weightSum += w;
    if (u.z * weightSum < w) {
      kept = light;
      keptTarget = target;
    }
  }
  float W = kept != DI_NO_LIGHT ? weightSum / keptTarget : 0.0;
  DiLightGridSlots(g.slots).v[slot] = uvec2(kept, floatBitsToUint(W));
}
