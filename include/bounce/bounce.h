// Bounce's public API: include this header and link bounce::bounce (CMake:
// find_package(bounce CONFIG REQUIRED) from an install, or add_subdirectory(bounce)).
//
//   bounce/scene.h             Scene: load a built-in scene or a glTF file, or build one in code
//                              (meshes, materials, instances), with a sun and a sky
//   bounce/camera.h            Camera: position, target, vertical field of view
//   bounce/settings.h          RendererSettings, Preset (mobile, desktop), GiMode, presetSettings
//   bounce/renderer.h          Renderer: render(camera) -> FrameStatistics, readImage(name)
//   bounce/frame_statistics.h  FrameStatistics: per-pass GPU milliseconds by name, frame index
//   bounce/image.h             Image (float RGBA), writeImage (.png, .exr)
//   bounce/external_device.h   ExternalDevice: bring your own VkInstance, VkDevice and queue
//   bounce/host_gbuffer.h      HostGBuffer, GiImage: bring your own G-buffer (Renderer::renderGi)
//   bounce/denoiser.h          Denoiser: SVGF, ReBLUR or the hybrid alone (noisy signal,
//                              depth, normal, motion in; denoised signal out)
//   bounce/error.h             Error: what every function throws for bad input or devices
//   bounce/math.h              Vec3, Mat4
//
// Entry points: Renderer::create(scene, settings) on a device Bounce creates;
// Renderer::create(externalDevice, scene, settings) on the host's device; and on that,
// Renderer::renderGi(camera, hostGBuffer): bring your own G-buffer (the host's rasterised
// G-buffer in, Bounce's diffuse GI image out; docs/library.md).
//
// Every type lives in namespace bounce (see bounce/config.h). Nothing here exposes Bounce's
// internal types; examples/ shows complete programs.
#pragma once
#include "bounce/camera.h"
#include "bounce/config.h"
#include "bounce/denoiser.h"
#include "bounce/error.h"
#include "bounce/external_device.h"
#include "bounce/frame_statistics.h"
#include "bounce/host_gbuffer.h"
#include "bounce/image.h"
#include "bounce/math.h"
#include "bounce/renderer.h"
#include "bounce/scene.h"
#include "bounce/settings.h"
