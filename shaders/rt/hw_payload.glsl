// The payload the hardware tracer's shaders pass back to the ray-generation shader: what
// TraceHit (rt/trace.glsl) reports, minus the facing. instance = BVH_INVALID on a miss.
#ifndef BOUNCE_RT_HW_PAYLOAD_GLSL
#define BOUNCE_RT_HW_PAYLOAD_GLSL

struct HwHit {
  float t;
  uint instance;  // GpuInstance index (the TLAS instance's custom index)
  uint geometry;  // global geometry index: the instance's geometryBase + the BLAS geometry index
  uint primitive;
  vec2 barycentrics;
};

const int HW_PAYLOAD_LOCATION = 0;

#endif
