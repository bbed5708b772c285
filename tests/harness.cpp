#include "harness.h"

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>

namespace bounce::test {

std::string sharedDir() {
  if (const char* env = std::getenv("BOUNCE_SHARED")) return env;
  return BOUNCE_SHARED_DIR;
}

std::string bounceExe() {
  if (const char* env = std::getenv("BOUNCE_EXE")) return env;
  return BOUNCE_EXE_PATH;
}

std::string tempDir(const std::string& tag) {
  auto dir = std::filesystem::temp_directory_path() /
             ("bounce-test-" + tag + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

CommandResult runCommand(const std::string& command, int timeoutSeconds) {
  CommandResult result;
  std::string full = "timeout " + std::to_string(timeoutSeconds) + " " + command + " 2>&1";
  FILE* pipe = ::popen(full.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

double meanLuminance(const ImageRGBA32F& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.pixelCount(); ++i)
    sum += 0.2126 * image.pixels[4 * i] + 0.7152 * image.pixels[4 * i + 1] +
           0.0722 * image.pixels[4 * i + 2];
  return sum / double(image.pixelCount());
}

glm::vec3 decodeOctahedral(glm::vec2 e) {
  glm::vec3 n(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
  if (n.z < 0.0f) {
    glm::vec2 folded = (1.0f - glm::abs(glm::vec2(n.y, n.x))) *
                       glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
    n.x = folded.x;
    n.y = folded.y;
  }
  return glm::normalize(n);
}

glm::vec3 gltfBrdf(const glm::vec3& c, float metallic, float roughness, const glm::vec3& wo,
                   const glm::vec3& wi) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const glm::vec3 n(0, 1, 0);
  float nl = glm::dot(n, wi), nv = glm::dot(n, wo);
  if (nl <= 0.0f || nv <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 h = glm::normalize(wo + wi);
  float a2 = roughness * roughness * roughness * roughness;
  float nh = glm::dot(n, h), vh = glm::dot(wo, h);
  float d = a2 / (kPi * std::pow(nh * nh * (a2 - 1.0f) + 1.0f, 2.0f));
  float v =
      0.5f / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
  float w = std::pow(1.0f - vh, 5.0f);
  float fd = 0.04f + 0.96f * w;
  glm::vec3 fm = c + (1.0f - c) * w;
  glm::vec3 dielectric = (1.0f - fd) * c / kPi + glm::vec3(fd * d * v);
  glm::vec3 metal = fm * d * v;
  return glm::mix(dielectric, metal, metallic);
}

glm::vec3 directionalAlbedo(const glm::vec3& c, float metallic, float roughness,
                            const glm::vec3& wo) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const int nTheta = 2000, nPhi = 1000;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nTheta; ++i) {
    float cosTheta = (i + 0.5f) / nTheta;
    float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
    for (int j = 0; j < nPhi; ++j) {
      float phi = 2.0f * kPi * (j + 0.5f) / nPhi;
      glm::vec3 wi(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
      sum += glm::dvec3(gltfBrdf(c, metallic, roughness, wo, wi) * cosTheta);
    }
  }
  return glm::vec3(sum * (2.0 * std::numbers::pi / (double(nTheta) * nPhi)));
}

}  // namespace bounce::test
