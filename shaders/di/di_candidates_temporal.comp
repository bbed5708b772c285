// di-candidates-temporal: di-generate-candidates and di-temporal in one pass, where no shadow ray
// comes between them (DiSettings::candidateVisibility off, the default): each pixel's candidates
// resampled (di_candidates.glsl, as di_generate_candidates.comp describes) and the kept one
// merged at once with last frame's reservoir (di_temporal_reuse.glsl, as di_temporal.comp
// describes). The candidate goes through the reservoir's packing as it would between the two
// passes (today an identity: resampleCandidates already quantises u, and M = 1 is exact as a
// half; kept so that the equality with the two passes holds by construction), so the output is
// the two passes' texel for texel, without the surface loaded twice, the candidate written and
// read back, or a dispatch (docs/di.md).
#version 460
#include "di/di_candidates.glsl"
#include "di/di_temporal_reuse.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  DiReservoir candidate = emptyDiReservoir();
  if (s.valid) {
    float target;
    candidate = resampleCandidates(f, di, s, pixel, target);
  }
  storeTemporalReuse(f, di, s, pixel, unpackDiReservoir(packDiReservoir(candidate)));
}
