// di-light-grid-view: the debug view di.grid-cells, declared only when it is requested
// (HybridFrame::requestDebugView): each pixel's light-grid cell, the one its candidates' lookup
// is centred on (without ReGIR's jitter), in a colour hashed from the cell's index (so the
// cells' edges show), brighter the more distinct lights the cell's slots hold; black where there
// is no surface or the point is outside the grid: the colour x (0.15 + 0.85 x the distinct
// lights among the cell's first 64 slots / those slots). Alpha 1.
#version 460
#include "di/light_grid.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_GRID_VIEW_BINDING_OUTPUT, rgba32f) uniform writeonly image2D viewOut;

const uint MAX_COUNTED_SLOTS = 64u;

uint slotLight(DiLightGrid g, uint cell, uint slot) {
  uvec2 entry = DiLightGridSlots(g.slots).v[cell * g.slotsPerCell + slot];
  return uintBitsToFloat(entry.y) > 0.0 ? entry.x : DI_NO_LIGHT;
}

// How many different lights the cell's first slots hold (empty slots not counted).
uint distinctLights(DiLightGrid g, uint cell, uint slots) {
  uint count = 0u;
  for (uint i = 0u; i < slots; ++i) {
    uint light = slotLight(g, cell, i);
    if (light == DI_NO_LIGHT) continue;
    bool seen = false;
    for (uint j = 0u; j < i && !seen; ++j) seen = slotLight(g, cell, j) == light;
    if (!seen) ++count;
  }
  return count;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  DiSurface s = loadDiSurface(f, pixel);
  vec4 view = vec4(0.0, 0.0, 0.0, 1.0);
  if (s.valid && di.lightGrid != 0ul) {
    DiLightGrid g = DiLightGridBlock(di.lightGrid).v;
    int cell = diLightGridCell(g, diLightGridOrigin(f, g), s.position);
    if (cell >= 0) {
      uint slots = min(g.slotsPerCell, MAX_COUNTED_SLOTS);
      uint distinct = distinctLights(g, uint(cell), slots);
      vec3 colour = vec3(0.3) + 0.7 * vec3(pcg4d(uvec4(uint(cell), 0x44490005u, 0u, 0u)).xyz & 0xFFu) / 255.0;
      view = vec4(colour * (0.15 + 0.85 * float(distinct) / float(slots)), 1.0);
    }
  }
  imageStore(viewOut, pixel, view);
}
