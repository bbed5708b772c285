#include "harness.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

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
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

}  // namespace bounce::test
