// scene-deform: poses every vertex of the deforming meshes (glTF morph targets, then skin) into
// the scene's vertex streams, keeping the pose before it in the previous positions for motion
// vectors. The same arithmetic as poseGeometry in src/scene/deformation.cpp.
#version 460
#include "shared/deform_io.h"

layout(local_size_x = DEFORM_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { DeformConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Geometries {
  GpuDeformGeometry v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Uints { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer RestVertices {
  GpuDeformVertex v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Deltas {
  GpuMorphDelta v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Rows { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec3s { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec4s { vec4 v[]; };

struct Posed {
  vec3 position;
  vec3 normal;
  vec3 tangent;
};

// p + sum_k w_k dp_k, and the same for the normal and tangent (glTF 2.0 §3.7.2.2).
void morph(GpuDeformGeometry g, uint local, inout Posed v) {
  Deltas deltas = Deltas(pc.deltas);
  Floats weights = Floats(pc.morphWeights);
  for (uint k = 0u; k < g.morphCount; ++k) {
    float w = weights.v[g.weightBase + k];
    if (w == 0.0) continue;
    GpuMorphDelta d = deltas.v[g.morphBase + k * g.vertexCount + local];
    v.position += w * d.position;
    v.normal += w * d.normal;
    v.tangent += w * d.tangent;
  }
}

// sum_i weight_i J[joint_i], as the three rows of an affine matrix (glTF 2.0 §3.7.3.3).
void skinRows(GpuDeformVertex r, uint jointBase, out vec4 rows[3]) {
  uvec4 joints = uvec4(r.joints01 & 0xFFFFu, r.joints01 >> 16, r.joints23 & 0xFFFFu,
                       r.joints23 >> 16);
  Rows jointRows = Rows(pc.jointRows);
  rows[0] = vec4(0.0);
  rows[1] = vec4(0.0);
  rows[2] = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    if (r.weights[i] == 0.0) continue;
    uint j = 3u * (jointBase + joints[i]);
    rows[0] += r.weights[i] * jointRows.v[j];
    rows[1] += r.weights[i] * jointRows.v[j + 1u];
    rows[2] += r.weights[i] * jointRows.v[j + 2u];
  }
}

vec3 normalizedOr(vec3 v, vec3 fallback) {
  float len = length(v);
  return len > 0.0 && !isinf(len) && !isnan(len) ? v / len : fallback;
}

void main() {
  uint vertex = gl_GlobalInvocationID.x;
  if (vertex >= pc.vertexCount) return;
  GpuDeformGeometry g = Geometries(pc.geometries).v[Uints(pc.geometryOfVertex).v[vertex]];
  GpuDeformVertex r = RestVertices(pc.rest).v[vertex];
  uint local = vertex - g.restBase;
  Posed v = Posed(r.position, r.normal, r.tangent.xyz);
  morph(g, local, v);
  if (g.jointBase != DEFORM_NO_SKIN) {
    vec4 rows[3];
    skinRows(r, g.jointBase, rows);
    mat3 linear = transpose(mat3(rows[0].xyz, rows[1].xyz, rows[2].xyz));
    v.position = vec3(dot(rows[0], vec4(v.position, 1.0)), dot(rows[1], vec4(v.position, 1.0)),
                      dot(rows[2], vec4(v.position, 1.0)));
    v.normal = linear * v.normal;
    v.tangent = linear * v.tangent;
  }
  uint target = g.firstVertex + local;
  Vec3s positions = Vec3s(pc.positions);
  Vec3s previous = Vec3s(pc.previousPositions);
  previous.v[target] = pc.keepPrevious != 0u ? positions.v[target] : v.position;
  positions.v[target] = v.position;
  Vec3s(pc.normals).v[target] = normalizedOr(v.normal, r.normal);
  Vec4s(pc.tangents).v[target] = vec4(normalizedOr(v.tangent, r.tangent.xyz), r.tangent.w);
}
