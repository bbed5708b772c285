// What both fuzz targets share: the parsers read paths, not memory, so each input is written to
// one file per process (rewritten for every input) whose extension picks the parser.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace bounce::fuzz {

// Writes the input to /tmp/bounce-fuzz-<target>-<pid>.<extension>; empty on failure.
inline std::string writeInputFile(const char* target, const char* extension, const uint8_t* data,
                                  size_t size) {
  const std::string path =
      "/tmp/bounce-fuzz-" + std::string(target) + "-" + std::to_string(getpid()) + "." + extension;
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return {};
  const bool written = std::fwrite(data, 1, size, file) == size;
  return std::fclose(file) == 0 && written ? path : std::string();
}

}  // namespace bounce::fuzz
