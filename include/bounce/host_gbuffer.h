// Bring your own G-buffer: the host rasterises (or otherwise computes) its own G-buffer on the
// device it gave Bounce (bounce/external_device.h) and Renderer::renderGi turns it into Bounce's
// diffuse GI. The host's images replace Bounce's vbuffer and gbuffer passes; everything after
// them (sun shadows, the chosen GI system with its denoisers) runs unchanged on the scene the
// Renderer was created with, which must be the scene the host rendered.
//
// The host's images (the contract; docs/library.md has it as a table):
//
//   image   format                         contents
//   depth   VK_FORMAT_R32_SFLOAT           linear view depth in metres, measured along the
//                                          camera's forward axis (not along the ray; a point p
//                                          has depth dot(p - camera.position, forward), forward
//                                          = normalize(camera.target - camera.position));
//                                          0 (or negative, NaN, infinite) means no surface (sky)
//   normal  VK_FORMAT_R16G16B16A16_SFLOAT  world-space unit shading normal in xyz, w ignored;
//                                          a normal facing away from the camera is flipped
//   albedo  VK_FORMAT_R8G8B8A8_UNORM       linear diffuse albedo in rgb (not sRGB-encoded),
//                                          a ignored
//   motion  VK_FORMAT_R16G16_SFLOAT        screen motion in pixels: this frame's pixel position
//                                          minus last frame's (x right, y down; 0 for a still
//                                          camera and scene)
//
// Every image: 2D, one layer and one mip, extent = the renderer's resolution (settings width x
// height), created with VK_IMAGE_USAGE_STORAGE_BIT (Bounce's own images are storage images of the
// same formats, so a device that runs Bounce supports them), `view` a VK_IMAGE_VIEW_TYPE_2D view
// of it with the same format, and in VK_IMAGE_LAYOUT_GENERAL when renderGi is called; Bounce
// only reads them and leaves them in GENERAL. The host's writes must have been submitted to the
// renderer's queue before renderGi (Bounce's first command is a barrier from all earlier work,
// ALL_COMMANDS / MEMORY_WRITE); writes from another queue need the host's own semaphore, waited
// for before renderGi. Bounce checks format, extent and handles (Vulkan cannot tell it the usage
// or layout; the Khronos validation layer on the host's instance can) and throws bounce::Error
// naming the image at fault.
//
// What the host does not give, Bounce fills with fixed values: no emission, metallic 0,
// perceptual roughness 1, the same normal as shading and geometric normal, no texture
// coordinates; a pixel is a surface where its depth is positive and finite.
//
// The camera passed with the frame must be the one the host rendered with: Bounce shoots the ray
// through pixel (x, y) as bounce/camera.h's pinhole camera does (pixel centres, y down, vertical
// field of view over the image height, aspect = width / height).
#pragma once
#include <cstdint>

#include <vulkan/vulkan.h>

#include "bounce/config.h"

namespace bounce::api {

// One of the host's images: its handles, and the format and extent it was created with (Vulkan
// cannot tell Bounce those).
struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

struct HostGBuffer {
  HostImage depth;   // VK_FORMAT_R32_SFLOAT
  HostImage normal;  // VK_FORMAT_R16G16B16A16_SFLOAT
  HostImage albedo;  // VK_FORMAT_R8G8B8A8_UNORM
  HostImage motion;  // VK_FORMAT_R16G16_SFLOAT
};

// What Renderer::renderGi returns: Bounce's image of the diffuse GI at each pixel, the outgoing
// diffuse radiance per unit albedo (irradiance / pi, W/(m^2 sr)); multiply by the albedo for the
// diffuse indirect light. rgb; alpha is Bounce's own. Where the depth said sky the
// value means nothing (the host ignores it).
//
// It is Bounce's image: the host reads it (as a storage image, or sampled in GENERAL, or copies
// it) and never writes or destroys it. It is valid until the next renderGi or render of the
// renderer, or its destruction. When renderGi returns the GPU work is complete and the image
// is in `layout`; like any write of an earlier submission, the host's first read needs a barrier
// from VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT / VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, and may
// transition it to another layout (Bounce does not read it back, and rewrites it from scratch).
// The host's reads must be submitted to the renderer's queue (or waited for) before the next
// renderGi: its first command is a barrier that waits for all earlier work on the queue.
struct GiImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  // VK_IMAGE_VIEW_TYPE_2D
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkFormat format = VK_FORMAT_UNDEFINED;  // VK_FORMAT_R16G16B16A16_SFLOAT
  uint32_t width = 0, height = 0;         // the renderer's resolution
};

}  // namespace bounce::api
