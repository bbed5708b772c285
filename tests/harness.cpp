#include "harness.h"

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

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

}  // namespace bounce::test
