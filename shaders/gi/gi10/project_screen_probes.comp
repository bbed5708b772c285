// gi10-project-screen-probes (§1.2 #20): each valid probe's 64 cells projected on L2 SH
// (9 coefficients per colour), each cell weighing its solid angle 2 pi / 64 (the cells are
// equal-area, gi10_common.glsl) at its centre direction. One thread per probe tile.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };

void main() {
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uint tileIndex = gl_GlobalInvocationID.x;
  if (tileIndex >= k.probeGrid.x * k.probeGrid.y) return;
  Gi10Probe probe = Gi10ProbesRef(k.probes).v[tileIndex];
  if ((probe.flags & GI10_PROBE_VALID) == 0u) return;
  Gi10RadianceRef radiance = Gi10RadianceRef(k.radiance);
  vec3 sh[9];
  for (uint i = 0u; i < 9u; ++i) sh[i] = vec3(0.0);
  const float cellSolidAngle = 2.0 * PI / float(GI10_PROBE_CELLS);
  for (uint cell = 0u; cell < GI10_PROBE_CELLS; ++cell) {
    vec3 l = gi10UnpackCell(radiance.v[tileIndex * GI10_PROBE_CELLS + cell]).rgb * cellSolidAngle;
    float y[9];
    gi10ShBasis(gi10HemisphereDirection(probe.normal, gi10CellCentre(cell)), y);
    for (uint i = 0u; i < 9u; ++i) sh[i] += l * y[i];
  }
  Gi10ShRef out_ = Gi10ShRef(k.sh);
  for (uint i = 0u; i < 9u; ++i) out_.v[tileIndex * 9u + i] = sh[i];
}
