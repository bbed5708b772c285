// Lets one header declare a struct for both C++ and GLSL (DESIGN.md §1: CPU/GPU structs are
// declared once). GLSL sees these headers through buffers declared `layout(scalar)`, so a C++
// struct made of glm vectors (tightly packed, 4-byte aligned) has the same layout; every shared
// struct carries a BOUNCE_CHECK_SIZE so a drift fails to compile.
#ifndef BOUNCE_SHARED_COMPAT_H
#define BOUNCE_SHARED_COMPAT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace bounce::gpu {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec2 = glm::ivec2;
using ivec4 = glm::ivec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
using DeviceAddress = uint64_t;
// GLSL built-ins that shared functions call unqualified.
using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::max;
using glm::min;
using glm::normalize;
}  // namespace bounce::gpu
#define BOUNCE_BEGIN_SHARED namespace bounce::gpu {
#define BOUNCE_END_SHARED }
#define BOUNCE_CHECK_SIZE(Type, bytes) \
  static_assert(sizeof(Type) == (bytes), #Type " must match its GLSL scalar layout")
#define BOUNCE_CONST inline constexpr
#define BOUNCE_FN inline
#define BOUNCE_PRECISE
#else
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// [[dont_unroll]]: loops whose unrolled copies a CPU driver would compile (docs/startup.md).
#extension GL_EXT_control_flow_attributes : require
// Ray counting (shaders/rt/trace.glsl) adds a subgroup's rays with one atomic.
#extension GL_KHR_shader_subgroup_ballot : require
#define BOUNCE_BEGIN_SHARED
#define BOUNCE_END_SHARED
#define BOUNCE_CHECK_SIZE(Type, bytes)
#define BOUNCE_CONST const
#define BOUNCE_FN
#define BOUNCE_PRECISE precise
#define DeviceAddress uint64_t
#endif

#endif
