// Output files checked before the work that fills them (DESIGN.md §7: "outputs are checked
// writable before any work starts"), and written with every failure reported: a long render
// must not be lost to a typo in --out, and a full disk must not pass in silence.
#pragma once
#include <string>
#include <vector>

namespace bounce {

// Makes sure `path` can be written as a file: creates its missing parent directories, then
// creates and removes the file (or, if it exists, opens it for appending without changing it).
// Throws bounce::Error naming `option` and the path, e.g. "--out 'a/b.png': cannot create the
// directory 'a': Not a directory".
void requireWritableFile(const std::string& option, const std::string& path);

// The same for a directory that will receive files: created when missing, probed with a file.
void requireWritableDirectory(const std::string& option, const std::string& directory);

// Throws bounce::Error naming `option` unless `path` ends in one of `extensions` (lower case,
// without the dot), e.g. "--out 'render': unknown image type (no extension); expected .png or
// .exr".
void requireExtension(const std::string& option, const std::string& path,
                      const std::vector<std::string>& extensions);

// Writes `text` to `path` (replacing it), checking the open, every write and the close.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace bounce
