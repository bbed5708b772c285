// gi10-update-radiance-cache (§1.2 #14, §1.4 "update"): each cell that probe rays hit this
// frame folds the mean of its new samples into its running mean, n = min(n_old + n_new,
// maxSampleCount), mean = lerp(mean_old, mean_new, min(n_new / n, 1)): the new samples weigh
// as many as they are, so the mean is one of the last maxSampleCount samples (a fresh cell, or
// a frame with maxSampleCount samples or more, takes the new mean). §1.4 reads lerp(..., 1 / n),
// which counts a frame's samples in n but weighs them as one: a cell that many probe rays hit
// then trails by 16 frames, and each bounce that feedback carries trails by as much again
// (docs/gi/gi10.md). Then clears its scratch. One thread per slot.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };

void main() {
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  Gi10CacheRef cache = Gi10CacheRef(k.cache);
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= (k.bucketMask + 1u) * GI10_BUCKET_SLOTS) return;
  uvec4 scratch = cache.v[slot].scratch;
  if (scratch.w == 0u) return;
  uint added = min(scratch.w, GI10_CACHE_MAX_FRAME_SAMPLES);
  vec3 mean = vec3(scratch.xyz) / (GI10_CACHE_QUANTIZE * float(added));
  uint old = cache.v[slot].sampleCount;
  uint n = min(old + added, k.maxSampleCount);
  float alpha = min(float(added) / float(n), 1.0);
  cache.v[slot].radiance = mix(cache.v[slot].radiance, mean, alpha);
  cache.v[slot].sampleCount = n;
  cache.v[slot].scratch = uvec4(0u);
}
