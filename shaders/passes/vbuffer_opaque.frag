// vbuffer (fragment stage, opaque materials): writes which triangle covers the pixel. Nothing
// here discards, so the depth test runs before the shader and hidden fragments cost nothing;
// alpha-tested materials are drawn after these with vbuffer_alpha_test.frag.
#version 460
#include "passes/hybrid_frame.glsl"

layout(early_fragment_tests) in;
layout(push_constant, scalar) uniform Push { VBufferDrawConstants pc; };

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inPrimitive;
layout(location = 0) out uvec4 outIds;

void main() {
  outIds = uvec4(pc.instance, pc.geometry, inPrimitive, 0u);
}
