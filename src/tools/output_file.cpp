#include "tools/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "tools/image_io.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

void createDirectory(const std::string& option, const std::string& path, const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error)
    fail("{} '{}': cannot create the directory '{}': {}", option, path, dir.string(),
         error.message());
  if (!fs::is_directory(dir)) fail("{} '{}': '{}' is not a directory", option, path, dir.string());
}

// Opening is the only test that tells the truth for every user (root included), every file
// system (read-only mounts, /proc) and every access-control scheme.
void probeFile(const std::string& option, const std::string& path, const std::string& file) {
  const bool existed = fs::exists(file);
  const int fd =
      ::open(file.c_str(), existed ? (O_WRONLY | O_APPEND) : (O_WRONLY | O_CREAT | O_EXCL), 0644);
  if (fd < 0) fail("{} '{}': cannot write '{}': {}", option, path, file, std::strerror(errno));
  ::close(fd);
  if (!existed) ::unlink(file.c_str());
}

}  // namespace

void requireWritableFile(const std::string& option, const std::string& path) {
  if (path.empty()) fail("{}: expected a file name, got an empty one", option);
  const fs::path p(path);
  if (fs::is_directory(p)) fail("{} '{}': is a directory; expected a file name", option, path);
  if (p.has_parent_path()) createDirectory(option, path, p.parent_path());
  probeFile(option, path, path);
}

void requireWritableDirectory(const std::string& option, const std::string& directory) {
  createDirectory(option, directory, fs::path(directory));
  probeFile(option, directory,
            (fs::path(directory) / (".bounce-write-test-" + std::to_string(::getpid()))).string());
}

void requireExtension(const std::string& option, const std::string& path,
                      const std::vector<std::string>& extensions) {
  const std::string ext = imageExtension(path);
  for (const std::string& e : extensions)
    if (ext == e) return;
  std::string expected;
  for (size_t i = 0; i < extensions.size(); ++i)
    expected += (i == 0 ? "." : i + 1 == extensions.size() ? " or ." : ", .") + extensions[i];
  fail("{} '{}': unknown file type ({}); expected {}", option, path,
       ext.empty() ? std::string("no extension") : "." + ext, expected);
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) fail("{}: cannot open for writing: {}", path, std::strerror(errno));
  file << text;
  file.close();
  if (!file) fail("{}: cannot write the file (disk full?)", path);
}

}  // namespace bounce
