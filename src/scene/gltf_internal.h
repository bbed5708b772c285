// Pieces of the glTF loader shared by its files (gltf_loader.cpp: file, nodes, cameras, lights;
// gltf_mesh.cpp: primitives; gltf_material.cpp: materials and images). Not a public API.
#pragma once
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <glm/glm.hpp>

#include "scene/gltf_accessor.h"
#include "scene/load_warnings.h"
#include "scene/scene.h"

namespace bounce::gltf {

// Non-fatal problems (skipped primitives, dropped triangles, ignored features) are collected
// in src.warnings, grouped (load_warnings.h), and loading goes on.
inline void warn(const Source& src, LoadWarning warning) {
  src.warnings.add(std::move(warning));
}

// A feature of the file that Bounce does not render (an extension, occlusion maps, skins...):
// one line per feature and file, with how many `things` use it and the first of them.
inline void warnIgnored(const Source& src, const std::string& feature, const std::string& things,
                        const std::string& where) {
  warn(src, {.group = feature, .things = things, .where = where});
}

// Extensions the loader reads (or that carry nothing to render, like XMP metadata).
bool isSupportedExtension(const std::string& name);
// The warning for an extension that is not supported, saying what is drawn instead; the same
// text wherever the extension is met, so that it is named once per file.
std::string ignoredExtensionWarning(const std::string& name);

// "node 3", or "node 3 ('Chair')" when the object has a name, for messages.
std::string describe(const char* kind, int index, const std::string& name);
// "mesh 2 ('Cube.003') primitive 0".
std::string describePrimitive(const Source& src, int mesh, int primitive);

// One glTF mesh primitive as a Geometry with every stream filled (normals computed when absent,
// zero UVs when absent) and zero-area triangles removed. Returns nothing, after a warning, for
// primitives we do not render (points, lines, empty). `material` is left for the caller.
std::optional<Geometry> loadPrimitive(const Source& src, int mesh, int primitive);

// Skins and morph targets of primitives (src/scene/gltf_skin.cpp).
//
// JOINTS_0 and WEIGHTS_0 of a primitive of a skinned mesh into g.joints and g.weights, the
// weights renormalised to sum 1 (JOINTS_1/WEIGHTS_1 are ignored with a warning). False when the
// primitive has neither. Throws naming the primitive and vertex for joints outside the skin's
// `jointCount`, negative or all-zero weights, or streams not sized like POSITION.
bool loadSkinWeights(const Source& src, int mesh, int primitive, size_t jointCount, Geometry& g);
// The POSITION, NORMAL and TANGENT deltas of the primitive's morph targets into g.morphTargets.
void loadMorphTargets(const Source& src, int mesh, int primitive, Geometry& g);
// The morph target count shared by every primitive of the mesh (0 = none); throws naming two
// primitives whose counts differ.
size_t morphTargetCount(const Source& src, int mesh);
// The rest weights of node `node`'s mesh: node.weights, else mesh.weights, else zeros.
std::vector<float> restMorphWeights(const Source& src, int node, size_t targets);
// Skin `skin`'s inverseBindMatrices, one per joint (identities when the skin has none).
std::vector<glm::mat4> loadInverseBindMatrices(const Source& src, int skin);
// Applies `toWorld` to a geometry's positions, normals, tangents and morph deltas.
void bakeTransform(Geometry& g, const glm::mat4& toWorld);

// A mesh instance made from an unskinned node, for animations: the node, the instance, the
// node's rest parent-to-world transform and, when an ancestor of the node is animated, the
// Scene::skeleton node it hangs under (TransformTrack::parentNode): its parent's, or its own
// with `placedBySkeleton` for an unanimated node given by a matrix, which has no TRS to track.
struct AnimatedInstance {
  int node = -1;
  uint32_t instance = 0;
  glm::mat4 parent{1.0f};
  int parentNode = -1;
  bool placedBySkeleton = false;
};
// What the file's animation channels can drive: instances of unskinned mesh nodes, skeleton
// nodes (Scene::skeleton index of a glTF node: skin joints, animated ancestors of mesh nodes,
// and their ancestors), the morphed mesh copy of a node (Scene::meshes index), and skinned mesh
// nodes (whose own transform glTF ignores).
struct AnimationTargets {
  std::vector<AnimatedInstance> instances;
  std::map<int, uint32_t> skeletonNodes;
  std::map<int, uint32_t> morphedMeshes;
  std::set<int> skinnedNodes;
};
// Reads the file's animations into `out` (src/scene/gltf_animation.cpp): a transform track for
// every instance that is animated or hangs under a skeleton node, joint tracks for animated
// skeleton nodes, morph weight tracks. `meshes` are Scene::meshes, for the morph target counts.
void loadAnimations(const Source& src, const AnimationTargets& targets,
                    const std::vector<Mesh>& meshes, SceneAnimation& out);

// Applies a 2D affine UV transform (KHR_texture_transform, as a 3x3 matrix) to every UV.
void transformUvs(Geometry& geometry, const glm::mat3& uvTransform);

// Converts the materials the scene uses, on first use, and the images their textures need.
// Materials are appended to scene.materials in order of first use, so unused materials (and
// their images) cost nothing.
class MaterialTable {
 public:
  MaterialTable(const Source& src, Scene& scene) : src_(src), scene_(scene) {}

  // Index in scene.materials of glTF material `gltfMaterial`; -1 = the default grey material.
  uint32_t sceneIndex(int gltfMaterial);
  // The UV transform to bake into geometry drawn with `gltfMaterial` (KHR_texture_transform),
  // or nothing when it has none.
  std::optional<glm::mat3> uvTransform(int gltfMaterial);
  // Guarantees at least one material (the default) so the scene is never without one.
  void ensureNotEmpty();
  // Decodes the images the converted materials refer to into scene.images (in parallel).
  void decodeImages();

 private:
  struct Converted {
    uint32_t sceneIndex;
    std::optional<glm::mat3> uvTransform;
  };
  const Converted& convert(int gltfMaterial);
  Material makeMaterial(int gltfMaterial, std::optional<glm::mat3>& uvTransform);
  int imageFor(int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
               const std::string& slot, int material, std::optional<glm::mat3>& uvTransform);

  void warnIgnoredSampler(int texture, const std::string& where);

  const Source& src_;
  Scene& scene_;
  std::map<int, Converted> converted_;  // glTF material -> scene material
  std::set<int> samplerChecked_;        // textures whose sampler was checked
  std::optional<uint32_t> defaultMaterial_;
  std::map<int, int> sceneImageOfGltfImage_;
  std::vector<int> gltfImageOfSceneImage_;  // decode list, in scene.images order
};

}  // namespace bounce::gltf
