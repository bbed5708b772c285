// The hybrid frame without GI (DESIGN.md §4, seed 000's "mobile hybrid renderer"): per-frame
// constants written by `scene-update`, the GBuffer layout, and each pass's push constants and
// bindings. Passes bind the scene at set 0 (shaders/rt/scene.glsl) and their images at set 1.
//
// Images, all at render resolution unless said otherwise:
//   vbuffer.ids        RGBA32_UINT  (instance, global geometry, primitive, front-facing);
//                                   instance = VBUFFER_NO_HIT where no triangle covers the pixel
//   vbuffer.depth      D32_SFLOAT   reversed Z with an infinite far plane: near / view depth
//   gbuffer.base-color RGBA16F      linear base colour (textures applied), metallic in w
//   gbuffer.normals    RGBA16F      octahedral shading normal (xy), geometric normal (zw); both
//                                   world space, on the viewer's side (history: reprojection)
//   gbuffer.depth      R32F         view depth (along the camera's forward axis), 0 for sky
//                                   (history: reprojection)
//   gbuffer.uv         RG32F        texture coordinates of the first UV set
//   gbuffer.velocity   RG16F        pixel position now minus pixel position last frame (camera
//                                   and object motion)
//   gbuffer.emissive   RGBA16F      emitted radiance (rgb), perceptual roughness in w
//   gbuffer.flags      R32_UINT     GBUFFER_FLAG_* bits
//   shadows.raw        R16F         sun visibility, one cone sample per pixel (1/divisor res)
//   shadows.visibility RG16F        denoised sun visibility (x), frames accumulated (y) (history)
//   sky.radiance       RGBA16F      sky radiance where no surface is seen, 0 elsewhere
//   di.radiance        RGBA16F      direct light of the light tables' lights (ReSTIR DI,
//   docs/di.md) gi.diffuse         RGBA16F      diffuse irradiance / pi from a GI mode (zero for
//   --gi none) reflections        RGBA16F      specular radiance from a reflection pass (zero for
//   now) composite.hdr      RGBA16F      scene-referred radiance (before exposure) tonemap.display
//   RGBA16F      display-referred linear colour in [0, 1]
//
// Bring your own G-buffer (`gbuffer-import`, include/bounce/host_gbuffer.h): the host's images,
// imported, storage images in GENERAL layout at render resolution:
//   host.depth         R32F         view depth in metres along the camera's forward axis
//                                   (as gbuffer.depth); 0 (or negative, NaN, inf): no surface
//   host.normal        RGBA16F      world-space unit normal in xyz (w ignored); turned toward
//                                   the viewer when it faces away
//   host.albedo        RGBA8        linear diffuse albedo in rgb (UNORM, not sRGB; a ignored)
//   host.motion        RG16F        as gbuffer.velocity: pixel position now minus last frame
#ifndef BOUNCE_SHARED_HYBRID_FRAME_IO_H
#define BOUNCE_SHARED_HYBRID_FRAME_IO_H
#include "shared/camera.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint VBUFFER_NO_HIT = 0xFFFFFFFFu;

BOUNCE_CONST uint GBUFFER_FLAG_SURFACE = 1u;       // a triangle covers the pixel (else sky)
BOUNCE_CONST uint GBUFFER_FLAG_BACK_FACING = 2u;   // the viewer sees the triangle's back face
BOUNCE_CONST uint GBUFFER_FLAG_ALPHA_TESTED = 4u;  // the material is MASK or BLEND

BOUNCE_CONST uint FRAME_FLAG_LAMBERT = 1u;  // every material pure Lambert (--lambert)
// ReSTIR DI lights the primary vertex from every light of the light tables (src/di/restir_di.h):
// composite adds di.radiance instead of its unshadowed loop over the KHR lights, and rays that
// leave the primary vertex (GI, reflections) count no emission of emitters the tables sample.
BOUNCE_CONST uint FRAME_FLAG_DI_LIGHTS = 2u;
// Instances moved or meshes deformed since the last frame (HybridFrame::setInstanceTransforms,
// setDeformation): light and shadow may change on pixels that do not move themselves, so
// shadows-denoise clamps its history everywhere, as it does where the view moves.
BOUNCE_CONST uint FRAME_FLAG_SCENE_MOVED = 4u;

BOUNCE_CONST uint FRAME_SKY_CONSTANT = 0u;
BOUNCE_CONST uint FRAME_SKY_DAYLIGHT = 1u;  // Preetham et al. 1999, shaders/common/sky.glsl

// Written once per frame by `scene-update` (vkCmdUpdateBuffer), read by every pass through a
// buffer reference. Matrices map world space to Vulkan clip space (y down, reversed Z).
struct FrameConstants {
  mat4 viewProjection;          // this frame's, jittered (see `jitter`)
  mat4 previousViewProjection;  // last frame's, for velocity and reprojection (see `jitter`)
  GpuCamera camera;             // the same camera as rays through pixel centres
  vec3 towardSun;               // unit
  float sunCosHalfAngle;        // cosine of half the sun's angular diameter
  vec3 sunIrradiance;           // E x colour, W/m^2 on a surface facing the sun; 0 = no sun
  uint skyModel;                // FRAME_SKY_*
  vec3 skyRadiance;             // constant sky
  float skyTurbidity;           // daylight sky
  float skyScale;               // daylight sky: radiance per kcd/m^2 of the model
  float skyAmbientStrength;     // placeholder ambient (unoccluded sky light), 0 = off
  float exposure;               // fixed exposure: 2^exposureStops (tonemap; auto exposure
                                // writes its own, shared/auto_exposure_io.h)
  uint frameIndex;
  uvec2 resolution;                 // render resolution
  uvec2 shadowResolution;           // shadows.raw
  uint shadowDivisor;               // render resolution / shadow resolution
  uint flags;                       // FRAME_FLAG_*
  DeviceAddress punctualLights;     // GpuPunctualLight[punctualLightCount]
  DeviceAddress directionalLights;  // GpuDistantLight[], KHR directional lights, not the sun
  uint punctualLightCount;
  uint directionalLightCount;
  float shadowMaxHistory;  // frames the shadow accumulation averages at most
  float nearPlane;         // of the reversed-Z projection
  // GpuInstance[], every instance's placement last frame (object motion in gbuffer.velocity);
  // equal to the scene's instances while nothing moves.
  DeviceAddress previousInstances;
  // vec4[SPECULAR_ALBEDO_SIZE^2], the split-sum table (shared/specular_albedo_io.h), for passes
  // that reflect light at surfaces their rays hit (the GI's and the cache's metals); 0: none.
  DeviceAddress specularAlbedo;
  // Sub-pixel offset of this frame's primary visibility in pixels, in [-0.5, 0.5) (temporal
  // anti-aliasing, src/passes/taa.h; 0 without it): the ray of pixel p passes through
  // p + 0.5 + jitter (pixelRayDirection), and viewProjection is shifted to match. Motion stays
  // unjittered: previousViewProjection is last frame's unjittered matrix shifted by this
  // frame's jitter alone, so a point that has not moved maps to the pixel that sees it now
  // and gbuffer.velocity is 0 on a static view whatever the jitter.
  vec2 jitter;
};
BOUNCE_CHECK_SIZE(FrameConstants, 336);

// Push constants of every hybrid-frame compute pass: the frame constants' address.
struct HybridPassConstants {
  DeviceAddress frame;  // FrameConstants
  uint historyValid;    // passes with history: 0 in the first frame and after a reset
  uint pad0;
};
BOUNCE_CHECK_SIZE(HybridPassConstants, 16);

// Push constants of tonemap: the frame and where its exposure comes from.
struct TonemapConstants {
  DeviceAddress frame;          // FrameConstants
  DeviceAddress exposureState;  // ExposureState of automatic exposure; 0: FrameConstants::exposure
};
BOUNCE_CHECK_SIZE(TonemapConstants, 16);

// Push constants of one vbuffer draw: one geometry of one instance.
struct VBufferDrawConstants {
  DeviceAddress frame;  // FrameConstants
  uint instance;
  uint geometry;  // global geometry index
};
BOUNCE_CHECK_SIZE(VBufferDrawConstants, 16);

// Set 1 bindings (storage images), per pass.
BOUNCE_CONST uint VBUFFER_TRACE_BINDING_IDS = 0u;
BOUNCE_CONST uint VBUFFER_TRACE_BINDING_COUNT = 1u;
BOUNCE_CONST uint GBUFFER_BINDING_IDS = 0u;
BOUNCE_CONST uint GBUFFER_BINDING_BASE_COLOR = 1u;
BOUNCE_CONST uint GBUFFER_BINDING_NORMALS = 2u;
BOUNCE_CONST uint GBUFFER_BINDING_DEPTH = 3u;
BOUNCE_CONST uint GBUFFER_BINDING_UV = 4u;
BOUNCE_CONST uint GBUFFER_BINDING_VELOCITY = 5u;
BOUNCE_CONST uint GBUFFER_BINDING_EMISSIVE = 6u;
BOUNCE_CONST uint GBUFFER_BINDING_FLAGS = 7u;
BOUNCE_CONST uint GBUFFER_BINDING_COUNT = 8u;

// gbuffer-import: the host's images in, the GBuffer out (the outputs as GBUFFER_BINDING_*).
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_HOST_DEPTH = 0u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_HOST_NORMAL = 1u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_HOST_ALBEDO = 2u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_HOST_MOTION = 3u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_BASE_COLOR = 4u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_NORMALS = 5u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_DEPTH = 6u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_UV = 7u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_VELOCITY = 8u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_EMISSIVE = 9u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_FLAGS = 10u;
BOUNCE_CONST uint GBUFFER_IMPORT_BINDING_COUNT = 11u;
// What gbuffer-import writes where the host has no say (documented in host_gbuffer.h).
BOUNCE_CONST float GBUFFER_IMPORT_ROUGHNESS = 1.0f;  // perceptual roughness: fully rough
BOUNCE_CONST float GBUFFER_IMPORT_METALLIC = 0.0f;   // dielectric

BOUNCE_CONST uint SHADOWS_TRACE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint SHADOWS_TRACE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint SHADOWS_TRACE_BINDING_FLAGS = 2u;
BOUNCE_CONST uint SHADOWS_TRACE_BINDING_RAW = 3u;
BOUNCE_CONST uint SHADOWS_TRACE_BINDING_COUNT = 4u;

BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_RAW = 0u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_NORMALS = 1u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_DEPTH = 2u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_FLAGS = 3u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_VELOCITY = 4u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_PREVIOUS_DEPTH = 5u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_PREVIOUS = 6u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_CURRENT = 7u;
BOUNCE_CONST uint SHADOWS_DENOISE_BINDING_COUNT = 8u;

BOUNCE_CONST uint SKY_BINDING_FLAGS = 0u;
BOUNCE_CONST uint SKY_BINDING_RADIANCE = 1u;
BOUNCE_CONST uint SKY_BINDING_COUNT = 2u;

BOUNCE_CONST uint COMPOSITE_BINDING_BASE_COLOR = 0u;
BOUNCE_CONST uint COMPOSITE_BINDING_NORMALS = 1u;
BOUNCE_CONST uint COMPOSITE_BINDING_DEPTH = 2u;
BOUNCE_CONST uint COMPOSITE_BINDING_EMISSIVE = 3u;
BOUNCE_CONST uint COMPOSITE_BINDING_FLAGS = 4u;
BOUNCE_CONST uint COMPOSITE_BINDING_SHADOWS = 5u;
BOUNCE_CONST uint COMPOSITE_BINDING_SKY = 6u;
BOUNCE_CONST uint COMPOSITE_BINDING_GI_DIFFUSE = 7u;
BOUNCE_CONST uint COMPOSITE_BINDING_REFLECTIONS = 8u;
BOUNCE_CONST uint COMPOSITE_BINDING_DIRECT = 9u;  // di.radiance (zero without ReSTIR DI)
BOUNCE_CONST uint COMPOSITE_BINDING_OUTPUT = 10u;
BOUNCE_CONST uint COMPOSITE_BINDING_COUNT = 11u;

BOUNCE_CONST uint TONEMAP_BINDING_HDR = 0u;
BOUNCE_CONST uint TONEMAP_BINDING_DISPLAY = 1u;
BOUNCE_CONST uint TONEMAP_BINDING_COUNT = 2u;

BOUNCE_CONST uint HYBRID_GROUP_SIZE = 8u;

BOUNCE_END_SHARED
#endif
