// di-light-grid: every slot of the world-space light grid (shared/di_light_grid_io.h) gets one
// local light by RIS (Talbot 2005) with the cell's target diCellTarget (light_grid.glsl), over
// a pool of DiLightGrid::buildCandidates alias-table candidates (drawn by power, pmf p) that the
// cell's slots share. One workgroup per cell: each of its DI_LIGHT_GRID_GROUP_SIZE threads draws
// its share of the pool, candidate x_j weighing p_hat(x_j) / (N p(x_j)) for the pool's N, and
// keeps one of its share by RIS. A slot then picks a thread with probability proportional to the
// thread's weight sum and takes the light that thread kept: the pool's candidate x_j with
// probability w_j / (sum of all weights), as one RIS over the whole pool would. The slot's
// W = (the pool's weight sum) / p_hat(x) is RIS's unbiased contribution weight, which
// di-generate-candidates uses as 1/pdf of the slot's light. Slots of a cell are correlated
// (they share the pool): each is still unbiased on its own, which is all the candidates' MIS
// weights need (docs/di.md, "The light grid"). A pool shared by the cell's slots reaches a
// cell's few nearby lights among thousands with N = 256 draws (the default) at 256 target
// evaluations, where slots drawing 8 candidates each (the earlier build) rarely found them. Rebuilt every frame
// with fresh random numbers for the camera-centred grid of this frame.
#version 460
#include "di/light_grid.glsl"

layout(local_size_x = DI_LIGHT_GRID_GROUP_SIZE) in;

shared float threadWeightSum[DI_LIGHT_GRID_GROUP_SIZE];
shared uint threadKept[DI_LIGHT_GRID_GROUP_SIZE];
shared float threadKeptTarget[DI_LIGHT_GRID_GROUP_SIZE];

// The thread whose weight sum covers x in the running sum of all threads' sums (the last with
// weight where rounding leaves x past the end).
uint threadAt(float x) {
  float running = 0.0;
  uint last = 0u;
  for (uint i = 0u; i < DI_LIGHT_GRID_GROUP_SIZE; ++i) {
    if (!(threadWeightSum[i] > 0.0)) continue;
    last = i;
    running += threadWeightSum[i];
    if (x < running) return i;
  }
  return last;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  DiLightGrid g = DiLightGridBlock(di.lightGrid).v;
  uint cell = gl_WorkGroupID.y * (g.cellsX * g.cellsY) + gl_WorkGroupID.x;
  uint thread = gl_LocalInvocationID.x;
  lightTables = LightTablesBlock(di.lights).v;
  vec3 lo, hi;
  diLightGridCellBox(g, diLightGridOrigin(f, g), cell, lo, hi);
  uvec4 key = pcg4d(uvec4(cell * DI_LIGHT_GRID_GROUP_SIZE + thread, f.frameIndex, RANDOM_DI_LIGHT_GRID,
                          di.seed * 0x9E3779B9u));

  // This thread's share of the pool, resampled to one light.
  uint share = g.buildCandidates / DI_LIGHT_GRID_GROUP_SIZE;
  float poolSize = float(share * DI_LIGHT_GRID_GROUP_SIZE);
  uint kept = DI_NO_LIGHT;
  float weightSum = 0.0, keptTarget = 0.0;
  [[dont_unroll]] for (uint i = 0u; i < share; ++i) {
    vec4 u = diRandom(key);
    float pmf;
    uint light = pickLocalLight(u.xy, pmf);
    float target = pmf > 0.0 ? diCellTarget(light, lo, hi) : 0.0;
    float w = target > 0.0 ? target / (poolSize * pmf) : 0.0;
    if (!(w > 0.0)) continue;
    weightSum += w;
    if (u.z * weightSum < w) {
      kept = light;
      keptTarget = target;
    }
  }
  threadWeightSum[thread] = weightSum;
  threadKept[thread] = kept;
  threadKeptTarget[thread] = keptTarget;
  barrier();

  float total = 0.0;
  for (uint i = 0u; i < DI_LIGHT_GRID_GROUP_SIZE; ++i) total += threadWeightSum[i];
  for (uint slot = thread; slot < g.slotsPerCell; slot += DI_LIGHT_GRID_GROUP_SIZE) {
    uvec2 entry = uvec2(DI_NO_LIGHT, floatBitsToUint(0.0));
    if (total > 0.0) {
      uint from = threadAt(diRandom(key).x * total);
      entry = uvec2(threadKept[from], floatBitsToUint(total / threadKeptTarget[from]));
    }
    DiLightGridSlots(g.slots).v[cell * g.slotsPerCell + slot] = entry;
  }
}
