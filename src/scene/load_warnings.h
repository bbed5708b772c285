// Warnings from loading a scene, grouped by kind, so that a problem repeated in 98 meshes prints
// as one line with a count and its first example instead of 98 near-identical lines:
//
//   dropped zero-area triangles: 98 primitives (196 triangles), e.g. mesh 3 ('Cube.003')
//   primitive 0
//
// A kind met once prints as its one occurrence: "mesh 3 ('Cube.003') primitive 0: dropped 2 of
// 12 triangles with zero area". The loader fills a LoadWarnings; its caller decides where the
// summary goes (the glTF loader's one-argument form prints it to stderr).
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace bounce {

struct LoadWarning {
  // What every occurrence of this kind says, without a place: "dropped zero-area triangles",
  // "KHR_materials_sheen is ignored". Occurrences with the same group are summarised together.
  std::string group;
  // What `where` names, plural, for the count: "primitives", "materials", "nodes".
  std::string things;
  // Where this occurrence is ("mesh 3 ('Cube') primitive 0"); empty for the whole file.
  std::string where;
  // This occurrence in full when it is the only one ("dropped 2 of 12 triangles with zero
  // area"); empty = the group's text.
  std::string detail;
  // A quantity summed over the group (e.g. the triangles dropped), shown when `unit` is set.
  uint64_t amount = 0;
  std::string unit;  // what `amount` counts, plural ("triangles")
};

class LoadWarnings {
 public:
  void add(LoadWarning warning);

  // One line per group, in the order the groups first occurred.
  std::vector<std::string> summary() const;
  // How many occurrences the group had (0 if none).
  uint64_t count(const std::string& group) const;
  bool empty() const { return groups_.empty(); }

  // Prints each summary line as "warning: <source>: <line>".
  void print(std::FILE* out, const std::string& source) const;

 private:
  struct Group {
    LoadWarning first;
    uint64_t occurrences = 0;
    uint64_t amount = 0;
  };
  std::vector<Group> groups_;  // a few groups per file, so a linear search is fine
};

}  // namespace bounce
