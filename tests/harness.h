// Helpers shared by the tests: where the shared data and the `bounce` program are, running
// the program as a subprocess to check its exit code and error text, and small image helpers.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "tools/image_io.h"

namespace bounce::test {

// ../shared beside the checkout (scenes, references).
std::string sharedDir();
// The built `bounce` program (BOUNCE_EXE, set by CTest).
std::string bounceExe();
// A fresh empty directory under the system temp dir for this test's files.
std::string tempDir(const std::string& tag);

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};
// Runs `command` through the shell with a time limit (seconds); a hang counts as failure with
// exitCode 124.
CommandResult runCommand(const std::string& command, int timeoutSeconds = 120);

// Mean Rec. 709 luminance of an image's RGB.
double meanLuminance(const ImageRGBA32F& image);
// A unit normal from the GBuffer's octahedral encoding (encodeOctahedral,
// shaders/passes/hybrid_frame.glsl).
glm::vec3 decodeOctahedral(glm::vec2 e);

// The glTF metallic-roughness BRDF (spec Appendix B), written independently of the shaders
// (common/brdf.glsl) for the tests to check them against: f = mix(dielectric, metal, metallic),
// dielectric = (1 - F(0.04)) c / pi + F(0.04) D V, metal = F(c) D V, Schlick F in v.h, GGX D,
// and the height-correlated Smith V that the Khronos sample renderer uses (the spec's appendix
// writes the separable G1 G1; see brdf.glsl). The normal is +Y.
glm::vec3 gltfBrdf(const glm::vec3& c, float metallic, float roughness, const glm::vec3& wo,
                   const glm::vec3& wi);
// Directional albedo: the integral of gltfBrdf cos over the hemisphere around +Y, by the
// midpoint rule in (cos theta, phi), fine enough for roughness >= 0.3.
glm::vec3 directionalAlbedo(const glm::vec3& c, float metallic, float roughness,
                            const glm::vec3& wo);

}  // namespace bounce::test
