// di-generate-candidates: each pixel's initial reservoir by resampled importance sampling
// (Talbot 2005; Bitterli et al. 2020, Alg. 3) over DiConstants::lightCandidates light candidates
// drawn by power (the alias table; distant lights uniformly) or, with the light grid, most of
// them from the pixel's grid cell (di/light_grid.glsl): candidate i gets the weight
// p_hat(y_i) m_i(y_i) W_i (with the alias table alone: p_hat(y_i) / (M p(y_i))). Without the
// grid and on glossy pixels, DiConstants::brdfCandidates BRDF-sampled candidates join
// (di_brdf_candidate.glsl: diTracesBrdfCandidate), and
// every candidate gets the balance-heuristic weight p_hat(y_i) / (M_L p_L(y_i) + M_B p_B(y_i)).
// (With the grid the light strategy's density is not known, only each slot's RIS weight, so the
// host turns the BRDF candidate off there: RestirDi's makeConstants.) The kept one y has
// W = (sum of weights) / p_hat(y) and M = 1.
// Its shadow ray (RTXDI's initial visibility) is di-trace-candidate-visibility's.
#version 460
#include "di/di_candidates.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_CANDIDATES_BINDING_RESERVOIR, rgba32ui) uniform writeonly uimage2D reservoirOut;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  DiReservoir r = emptyDiReservoir();
  if (s.valid) {
    float target;
    r = resampleCandidates(f, di, s, pixel, target);
  }
  imageStore(reservoirOut, pixel, packDiReservoir(r));
}
