// Direction sampling.
#ifndef BOUNCE_COMMON_SAMPLING_GLSL
#define BOUNCE_COMMON_SAMPLING_GLSL

const float PI = 3.14159265358979;

// An orthonormal basis around n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void orthonormalBasis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction on the hemisphere around n (pdf = cos / pi).
vec3 sampleCosineHemisphere(vec3 n, vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  vec3 t, b;
  orthonormalBasis(n, t, b);
  return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u.x)) * n);
}

// Uniform direction in the cone of half-angle theta around axis (for the sun's disc).
vec3 sampleCone(vec3 axis, float cosThetaMax, vec2 u) {
  float cosTheta = mix(1.0, cosThetaMax, u.x);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.y;
  vec3 t, b;
  orthonormalBasis(axis, t, b);
  return normalize(sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * axis);
}

// Multiple importance sampling weight of strategy A against B, power heuristic with beta = 2
// (Veach 1997, "Robust Monte Carlo Methods for Light Transport Simulation", §9.2.3).
float powerHeuristic(float pdfA, float pdfB) {
  float a = pdfA * pdfA;
  float b = pdfB * pdfB;
  return a + b > 0.0 ? a / (a + b) : 0.0;
}

#endif
