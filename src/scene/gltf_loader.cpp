// glTF 2.0 loader on Debian's tinygltf 2.7: reads the file (checking the GLB layout itself),
// lets tinygltf parse the JSON and buffers, then walks the default scene's node trees into
// instances, the first perspective camera and KHR_lights_punctual lights. A node with a skin or
// a morphed mesh gets its own copy of the mesh (a deforming mesh has one instance); the joints
// of the skins, the parents of mesh nodes with an animated ancestor, and their ancestors become
// Scene::skeleton (gltf_animation.cpp hangs those meshes under it). Primitives are in
// gltf_mesh.cpp, their
// skin and morph streams in gltf_skin.cpp, materials and images in gltf_material.cpp, accessor
// reads in gltf_accessor.cpp.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <set>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "scene/gltf_internal.h"
#include "scene/load.h"

namespace bounce {
namespace {

using gltf::Source;
using gltf::warn;
using gltf::warnIgnored;

// tinygltf takes 32-bit lengths.
constexpr uint64_t kMaxFileBytes = 0xFFFFFFFFull;
// Deeper hierarchies are corrupt files in practice; the limit also bounds the recursion.
constexpr int kMaxNodeDepth = 1024;
// Primitives may share accessors, so a small file can name the same large accessor thousands
// of times; capping the total vertex + index count keeps memory bounded (2^28 is far above
// any real-time scene: 150 million triangles with unshared vertices).
constexpr uint64_t kMaxSceneElements = uint64_t(1) << 28;
constexpr uint32_t kGlbChunkJson = 0x4E4F534A;
constexpr uint32_t kGlbChunkBin = 0x004E4942;

std::vector<uint8_t> readFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    fail("{}: cannot open file: it is a directory", path);
  uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) fail("{}: cannot open file ({})", path, ec.message());
  if (size == 0) fail("{}: file is empty", path);
  if (size > kMaxFileBytes)
    fail("{}: file is {} bytes; files over 4 GiB are not supported", path, size);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open file", path);
  std::vector<uint8_t> bytes(size);
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
  if (uint64_t(in.gcount()) != size)
    fail("{}: read error after {} of {} bytes", path, in.gcount(), size);
  return bytes;
}

uint32_t readU32(const std::vector<uint8_t>& bytes, uint64_t offset) {
  uint32_t v;  // GLB is little-endian, like every machine we build for
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

bool hasGlbMagic(const std::vector<uint8_t>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

std::string printableMagic(const std::vector<uint8_t>& bytes) {
  std::string s;
  for (size_t i = 0; i < std::min<size_t>(4, bytes.size()); ++i)
    s += std::isprint(bytes[i]) ? char(bytes[i]) : '?';
  return s;
}

// GLB (glTF 2.0 §4.4): a 12-byte header (magic, version 2, total length), a JSON chunk and an
// optional BIN chunk, each behind an 8-byte (length, type) header. Checked here because
// tinygltf 2.7 lets a BIN chunk run 8 bytes past the end of the data.
void checkGlbLayout(const std::string& path, const std::vector<uint8_t>& bytes) {
  if (bytes.size() < 20)
    fail("{}: truncated binary glTF: {} bytes, the headers alone need 20", path, bytes.size());
  uint32_t version = readU32(bytes, 4);
  if (version != 2) fail("{}: binary glTF version {} is not supported (expected 2)", path, version);
  uint64_t length = readU32(bytes, 8);
  if (length > bytes.size())
    fail("{}: truncated binary glTF: the header declares {} bytes but the file has {}", path,
         length, bytes.size());
  uint64_t jsonEnd = 20 + uint64_t(readU32(bytes, 12));
  if (readU32(bytes, 16) != kGlbChunkJson) fail("{}: binary glTF: first chunk is not JSON", path);
  if (jsonEnd > length)
    fail("{}: truncated binary glTF: the JSON chunk ends at byte {}, past the declared length {}",
         path, jsonEnd, length);
  if (jsonEnd + 8 > length) return;  // no BIN chunk
  uint64_t binEnd = jsonEnd + 8 + readU32(bytes, jsonEnd);
  if (readU32(bytes, jsonEnd + 4) == kGlbChunkBin && binEnd > length)
    fail("{}: truncated binary glTF: the BIN chunk ends at byte {}, past the declared length {}",
         path, binEnd, length);
}

// tinygltf converts `extras` and `extensions` to its Value type recursively, so a file nested
// a hundred thousand levels deep overflows the stack. Real glTF stays a few levels deep; the
// limit leaves ample room for extras. Brackets inside strings do not count.
void checkJsonNesting(const std::string& path, const uint8_t* text, size_t size) {
  constexpr int kMaxJsonDepth = 256;
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < size; ++i) {
    char c = char(text[i]);
    if (inString) {
      if (c == '\\')
        ++i;  // skip the escaped character
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth)
        fail("{}: invalid JSON: nested deeper than {} levels", path, kMaxJsonDepth);
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

// tinygltf image callback: keep the encoded bytes instead of decoding, so only images that a
// used material needs are decoded, in parallel, with our own size checks (gltf_material.cpp).
// Images in buffer views are left alone: their view is range-checked before it is read.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf's messages end in newlines and may quote raw bytes of a corrupt file; make them one
// printable line.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n')
      c = ';';
    else if (!std::isprint(static_cast<unsigned char>(c)))
      c = '?';
  return text;
}

// tinygltf's own warnings, one group per distinct line.
void collectTinygltfWarnings(const std::string& text, LoadWarnings& warnings) {
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) warnings.add({.group = oneLine(text.substr(start, end - start))});
    start = end + 1;
  }
}

std::string lowercaseExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

tinygltf::Model parseModel(const std::string& path, LoadWarnings& loadWarnings) {
  std::vector<uint8_t> bytes = readFile(path);
  bool binary = hasGlbMagic(bytes);
  if (lowercaseExtension(path) == ".glb" && !binary)
    fail("{}: not a binary glTF: bad magic '{}' (expected 'glTF')", path, printableMagic(bytes));
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::string baseDir = parent.empty() ? std::string(".") : parent.string();

  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&keepEncodedImage, nullptr);
  tinygltf::Model model;
  std::string error, warnings;
  bool ok;
  if (binary) {
    checkGlbLayout(path, bytes);
    checkJsonNesting(path, bytes.data() + 20, readU32(bytes, 12));
    ok = parser.LoadBinaryFromMemory(&model, &error, &warnings, bytes.data(),
                                     unsigned(readU32(bytes, 8)), baseDir);
  } else {
    checkJsonNesting(path, bytes.data(), bytes.size());
    ok = parser.LoadASCIIFromString(&model, &error, &warnings,
                                    reinterpret_cast<const char*>(bytes.data()),
                                    unsigned(bytes.size()), baseDir);
  }
  collectTinygltfWarnings(warnings, loadWarnings);
  if (!ok) {
    if (error.find("json.exception.parse_error") != std::string::npos)
      fail("{}: invalid JSON: {}", path, oneLine(error));
    fail("{}: cannot load glTF: {}", path, oneLine(error.empty() ? "unknown error" : error));
  }
  return model;
}

void checkVersion(const std::string& path, const tinygltf::Model& model) {
  const std::string& v = model.asset.version;
  if (v.size() < 2 || v[0] != '2' || v[1] != '.')
    fail("{}: glTF version '{}' is not supported (expected 2.x)", path, v);
}

// Extensions we can honour or safely ignore when a file marks them required: the ones we load,
// and material extensions that only refine shading (the base metallic-roughness material stays
// a fair approximation). Spec-gloss is excluded: it replaces the material model altogether.
bool isSupportedRequiredExtension(const std::string& name) {
  if (gltf::isSupportedExtension(name)) return true;
  return name.starts_with("KHR_materials_") && name != "KHR_materials_pbrSpecularGlossiness";
}

void checkRequiredExtensions(const std::string& path, const tinygltf::Model& model) {
  for (const std::string& name : model.extensionsRequired)
    if (!isSupportedRequiredExtension(name))
      fail("{}: requires unsupported extension {}", path, name);
}

bool isFinite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// A transform that flattens space (a scale of 0 on some axis) cannot be inverted, so rays cannot
// be taken into its object space; glTF animations use scale 0 to hide objects.
bool isSingular(const glm::mat4& m) {
  float det = glm::determinant(glm::mat3(m));
  return !(std::abs(det) > 0.0f) || !isFinite(glm::inverse(m));
}

// Nodes whose translation, rotation or scale an animation drives.
std::set<int> animatedNodes(const tinygltf::Model& model) {
  std::set<int> nodes;
  for (const tinygltf::Animation& animation : model.animations)
    for (const tinygltf::AnimationChannel& channel : animation.channels)
      if (channel.target_path != "weights") nodes.insert(channel.target_node);
  return nodes;
}

std::optional<glm::vec3> unitDirection(const glm::mat4& toWorld, glm::vec3 local) {
  glm::vec3 d(toWorld * glm::vec4(local, 0.0f));
  float length = glm::length(d);
  if (!std::isfinite(length) || length <= 0.0f) return std::nullopt;
  return d / length;
}

class SceneBuilder {
 public:
  explicit SceneBuilder(const Source& src)
      : src_(src), materials_(src, scene_), animatedNodes_(animatedNodes(src.model)) {}

  Scene build(const std::string& name) {
    nodeState_.assign(src_.model.nodes.size(), NodeState::Unvisited);
    findParents();
    for (int root : rootNodes()) visitNode(root, glm::mat4(1.0f), 0, "the scene");
    hangUnderAnimatedAncestors();
    gltf::loadAnimations(src_, animationTargets_, scene_.meshes, scene_.animation);
    materials_.ensureNotEmpty();
    materials_.decodeImages();
    warnUnusedExtensions();
    scene_.name = name;
    validateScene(scene_, src_.path);
    return std::move(scene_);
  }

 private:
  enum class NodeState : uint8_t { Unvisited, Visiting, Done };

  // The default scene, else scene 0. A file with nodes but no scenes is most likely a sloppy
  // export rather than an intentionally empty file, so then every parentless node is a root.
  std::vector<int> rootNodes() const {
    const tinygltf::Model& model = src_.model;
    if (!model.scenes.empty()) {
      int s = model.defaultScene >= 0 ? model.defaultScene : 0;
      if (size_t(s) >= model.scenes.size())
        fail("{}: default scene {} does not exist ({} scenes)", src_.path, s, model.scenes.size());
      if (model.scenes.size() > 1)
        warn(src_, {.group = fmt::format("the file has {} scenes; only scene {} is loaded",
                                         model.scenes.size(), s)});
      return model.scenes[size_t(s)].nodes;
    }
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes)
      for (int child : node.children)
        if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
    return roots;
  }

  void visitNode(int index, const glm::mat4& parentToWorld, int depth,
                 const std::string& referrer) {
    if (index < 0 || size_t(index) >= src_.model.nodes.size())
      fail("{}: {} refers to node {} ({} nodes)", src_.path, referrer, index,
           src_.model.nodes.size());
    NodeState& state = nodeState_[size_t(index)];
    if (state == NodeState::Visiting)
      fail("{}: the node hierarchy has a cycle through node {}", src_.path, index);
    if (state == NodeState::Done)
      fail("{}: node {} is reached twice (nodes must form disjoint trees)", src_.path, index);
    if (depth > kMaxNodeDepth)
      fail("{}: the node hierarchy is deeper than {} levels", src_.path, kMaxNodeDepth);
    state = NodeState::Visiting;

    const tinygltf::Node& node = src_.model.nodes[size_t(index)];
    glm::mat4 toWorld = parentToWorld * localTransform(index);
    if (!isFinite(toWorld))
      fail("{}: {} has a non-finite world transform", src_.path,
           gltf::describe("node", index, node.name));
    // A skinned node's own transform is ignored (glTF 2.0 §3.7.3.1), singular or not.
    bool skinned = node.mesh >= 0 && node.skin >= 0;
    if (node.mesh >= 0 && (skinned || placeable(index, toWorld))) {
      size_t before = scene_.instances.size();
      addInstance(index, toWorld);
      if (scene_.instances.size() > before && !skinned)
        animationTargets_.instances.push_back({index, uint32_t(before), parentToWorld});
    }
    if (node.camera >= 0) addCamera(index, toWorld);
    addLight(index, toWorld);
    for (int child : node.children)
      visitNode(child, toWorld, depth + 1, fmt::format("node {}", index));
    state = NodeState::Done;
  }

  // The node's matrix, or T * R * S (glTF 2.0 §3.5.3), as float; any component that is not
  // finite after the conversion (1e39 in the file) is an error.
  glm::mat4 localTransform(int index) const {
    const tinygltf::Node& n = src_.model.nodes[size_t(index)];
    auto checkSize = [&](const std::vector<double>& v, size_t expected, const char* what) {
      if (!v.empty() && v.size() != expected)
        fail("{}: node {} {} has {} numbers, expected {}", src_.path, index, what, v.size(),
             expected);
    };
    checkSize(n.matrix, 16, "matrix");
    checkSize(n.translation, 3, "translation");
    checkSize(n.rotation, 4, "rotation");
    checkSize(n.scale, 3, "scale");
    glm::mat4 m(1.0f);
    if (!n.matrix.empty()) {
      for (int i = 0; i < 16; ++i)
        glm::value_ptr(m)[i] = float(n.matrix[size_t(i)]);  // column-major, as glTF
    } else {
      glm::vec3 t =
          n.translation.empty() ? glm::vec3(0.0f) : glm::vec3(glm::make_vec3(n.translation.data()));
      glm::vec3 s = n.scale.empty() ? glm::vec3(1.0f) : glm::vec3(glm::make_vec3(n.scale.data()));
      glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
      if (!n.rotation.empty())  // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z)
        q = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                      float(n.rotation[2]));
      float qLength = glm::length(q);
      if (!std::isfinite(qLength) || qLength == 0.0f)
        fail("{}: {} has a non-finite or zero rotation quaternion", src_.path,
             gltf::describe("node", index, n.name));
      m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(q / qLength) *
          glm::scale(glm::mat4(1.0f), s);
    }
    if (!isFinite(m))
      fail("{}: {} has a non-finite transform", src_.path, gltf::describe("node", index, n.name));
    return m;
  }

  // A mesh node whose world transform is singular (scale 0: how animations hide objects) has
  // nothing to show. Without an animation of its own it is skipped; with one it is kept, and
  // the renderer hides it while its transform stays singular (rt/scene_bvh.h).
  bool placeable(int index, const glm::mat4& toWorld) {
    if (!isSingular(toWorld)) return true;
    const tinygltf::Node& node = src_.model.nodes[size_t(index)];
    if (animatedNodes_.count(index) || hasAnimatedAncestor(index)) {
      warn(src_, {.group = "starts with a singular transform (scale 0): hidden until its "
                           "animation scales it up",
                  .things = "nodes",
                  .where = gltf::describe("node", index, node.name)});
      return true;
    }
    warn(src_, {.group = "skipped: singular transform (scale 0), nothing to show",
                .things = "nodes",
                .where = gltf::describe("node", index, node.name)});
    return false;
  }

  void addInstance(int index, const glm::mat4& toWorld) {
    const tinygltf::Node& node = src_.model.nodes[size_t(index)];
    if (size_t(node.mesh) >= src_.model.meshes.size())
      fail("{}: node {} refers to mesh {} ({} meshes)", src_.path, index, node.mesh,
           src_.model.meshes.size());
    int skin = node.skin >= 0 ? sceneSkin(node.skin, index) : -1;
    size_t targets = gltf::morphTargetCount(src_, node.mesh);
    std::optional<uint32_t> mesh;
    if (skin >= 0 || targets > 0) {
      Deformer deformer{index, skin, targets, toWorld};
      std::optional<Mesh> copy = loadMesh(node.mesh, &deformer);
      if (copy) {
        mesh = uint32_t(scene_.meshes.size());
        scene_.meshes.push_back(std::move(*copy));
        if (targets > 0) animationTargets_.morphedMeshes[index] = *mesh;
        if (skin >= 0) animationTargets_.skinnedNodes.insert(index);
      }
    } else {
      mesh = sceneMesh(node.mesh);
    }
    if (!mesh) return;
    std::string name = node.name.empty() ? fmt::format("node {}", index) : node.name;
    // The joints place a skinned mesh's vertices in the world.
    scene_.instances.push_back(Instance{*mesh, skin >= 0 ? glm::mat4(1.0f) : toWorld, name});
  }

  // Loads a glTF mesh on first use; several nodes sharing it share one scene Mesh (instancing).
  // Meshes without any triangle primitive give no Mesh and their nodes no instance.
  std::optional<uint32_t> sceneMesh(int gltfMesh) {
    auto cached = meshes_.find(gltfMesh);
    if (cached != meshes_.end()) return cached->second;
    std::optional<Mesh> mesh = loadMesh(gltfMesh, nullptr);
    std::optional<uint32_t> result;
    if (mesh) {
      result = uint32_t(scene_.meshes.size());
      scene_.meshes.push_back(std::move(*mesh));
    }
    meshes_.emplace(gltfMesh, result);
    return result;
  }

  // What makes a node's copy of a mesh deform: the node (whose weights and world transform the
  // copy needs), its skin (Scene::skins index, -1 = none) and the mesh's morph target count.
  struct Deformer {
    int node = -1;
    int skin = -1;
    size_t targets = 0;
    glm::mat4 toWorld{1.0f};
  };

  // The triangle primitives of a glTF mesh, with their skin and morph streams when `deformer`
  // is given; nothing, after a warning, when the mesh has no triangles.
  std::optional<Mesh> loadMesh(int gltfMesh, const Deformer* deformer) {
    const tinygltf::Mesh& source = src_.model.meshes[size_t(gltfMesh)];
    Mesh mesh;
    mesh.name = source.name.empty() ? fmt::format("mesh {}", gltfMesh) : source.name;
    for (size_t p = 0; p < source.primitives.size(); ++p) {
      std::optional<Geometry> geometry = gltf::loadPrimitive(src_, gltfMesh, int(p));
      if (!geometry) continue;
      loadedElements_ += geometry->positions.size() + geometry->indices.size();
      if (loadedElements_ > kMaxSceneElements)
        fail("{}: the scene has more than 2^28 vertices and indices in total", src_.path);
      int material = source.primitives[p].material;
      if (material >= int(src_.model.materials.size()))
        fail("{}: mesh {} primitive {} refers to material {} ({} materials)", src_.path, gltfMesh,
             p, material, src_.model.materials.size());
      geometry->material = materials_.sceneIndex(material);
      if (std::optional<glm::mat3> uvTransform = materials_.uvTransform(material))
        gltf::transformUvs(*geometry, *uvTransform);
      if (deformer) {
        addDeformation(gltfMesh, int(p), *deformer, *geometry);
        // Morph targets may share one large accessor, like primitives: they count too.
        for (const MorphTarget& target : geometry->morphTargets)
          loadedElements_ +=
              target.positions.size() + target.normals.size() + target.tangents.size();
        if (loadedElements_ > kMaxSceneElements)
          fail("{}: the scene has more than 2^28 vertices, indices and morph deltas in total",
               src_.path);
      }
      mesh.geometries.push_back(std::move(*geometry));
    }
    if (mesh.geometries.empty()) {
      warn(src_, {.group = "no triangles to render, nodes using it are skipped",
                  .things = "meshes",
                  .where = gltf::describe("mesh", gltfMesh, source.name)});
      return std::nullopt;
    }
    if (deformer) {
      mesh.skin = deformer->skin;
      if (deformer->targets > 0)
        mesh.morphWeights = gltf::restMorphWeights(src_, deformer->node, deformer->targets);
    }
    return mesh;
  }

  // The morph targets and joint influences of one primitive of a deforming node's mesh copy. A
  // primitive of a skinned mesh without JOINTS_0 and WEIGHTS_0 cannot follow the joints; it is
  // drawn where an unskinned node would draw it, at the node's rest world transform (baked into
  // its vertices, since the skinned instance has the identity transform), with a warning.
  void addDeformation(int gltfMesh, int primitive, const Deformer& deformer, Geometry& g) {
    if (deformer.targets > 0) gltf::loadMorphTargets(src_, gltfMesh, primitive, g);
    if (deformer.skin < 0) return;
    size_t jointCount = scene_.skins[size_t(deformer.skin)].joints.size();
    if (gltf::loadSkinWeights(src_, gltfMesh, primitive, jointCount, g)) return;
    warn(src_, {.group = "primitives of a skinned mesh without JOINTS_0 and WEIGHTS_0 stay rigid "
                         "at their node's rest transform",
                .things = "primitives",
                .where = gltf::describePrimitive(src_, gltfMesh, primitive)});
    gltf::bakeTransform(g, deformer.toWorld);
  }

  // glTF skin `gltfSkin` as a Scene::skins index, converted on first use (by node `node`), its
  // joints and their ancestors added to the skeleton.
  int sceneSkin(int gltfSkin, int node) {
    if (size_t(gltfSkin) >= src_.model.skins.size())
      fail("{}: node {} refers to skin {} ({} skins)", src_.path, node, gltfSkin,
           src_.model.skins.size());
    auto cached = skins_.find(gltfSkin);
    if (cached != skins_.end()) return cached->second;
    const tinygltf::Skin& source = src_.model.skins[size_t(gltfSkin)];
    std::string what = gltf::describe("skin", gltfSkin, source.name);
    if (source.joints.empty()) fail("{}: {} has no joints", src_.path, what);
    Skin skin;
    skin.name = source.name.empty() ? fmt::format("skin {}", gltfSkin) : source.name;
    for (int joint : source.joints) {
      if (size_t(joint) >= src_.model.nodes.size())
        fail("{}: {} has joint node {} ({} nodes)", src_.path, what, joint,
             src_.model.nodes.size());
      skin.joints.push_back(skeletonNode(joint));
    }
    skin.inverseBindMatrices = gltf::loadInverseBindMatrices(src_, gltfSkin);
    int index = int(scene_.skins.size());
    scene_.skins.push_back(std::move(skin));
    skins_.emplace(gltfSkin, index);
    return index;
  }

  // Scene::skeleton index of glTF node `node`, added (after its ancestors, so that parents come
  // before children) on first use.
  uint32_t skeletonNode(int node) {
    std::vector<int> chain;  // node and its ancestors not in the skeleton yet, child first
    for (int n = node; n >= 0 && !animationTargets_.skeletonNodes.count(n);
         n = parents_[size_t(n)]) {
      chain.push_back(n);
      if (chain.size() > size_t(kMaxNodeDepth))
        fail("{}: the ancestors of skin joint node {} loop or are deeper than {} levels", src_.path,
             node, kMaxNodeDepth);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const tinygltf::Node& n = src_.model.nodes[size_t(*it)];
      int parent = parents_[size_t(*it)];
      SkeletonNode skeletonNode;
      skeletonNode.name = n.name.empty() ? fmt::format("node {}", *it) : n.name;
      skeletonNode.parent = parent < 0 ? -1 : int(animationTargets_.skeletonNodes.at(parent));
      skeletonNode.local = localTransform(*it);
      animationTargets_.skeletonNodes[*it] = uint32_t(scene_.skeleton.size());
      scene_.skeleton.push_back(skeletonNode);
    }
    return animationTargets_.skeletonNodes.at(node);
  }

  // Whether a translation, rotation or scale channel drives an ancestor of glTF node `node`.
  bool hasAnimatedAncestor(int node) const {
    size_t steps = 0;
    for (int n = parents_[size_t(node)]; n >= 0 && steps <= size_t(kMaxNodeDepth);
         n = parents_[size_t(n)], ++steps)
      if (animatedNodes_.count(n)) return true;
    return false;
  }

  // An unskinned mesh node below an animated ancestor follows it: the instance hangs under its
  // parent's skeleton node, added with its ancestors (shared with the skins' joints). A node
  // given by a matrix has no TRS for its track, so unless it is animated (an error in
  // restTrack, as glTF allows animating TRS nodes only) it hangs under its own skeleton node.
  void hangUnderAnimatedAncestors() {
    for (gltf::AnimatedInstance& i : animationTargets_.instances) {
      if (!hasAnimatedAncestor(i.node)) continue;
      const tinygltf::Node& node = src_.model.nodes[size_t(i.node)];
      i.placedBySkeleton = !node.matrix.empty() && !animatedNodes_.count(i.node);
      if (i.placedBySkeleton) i.parent = i.parent * localTransform(i.node);
      i.parentNode = int(skeletonNode(i.placedBySkeleton ? i.node : parents_[size_t(i.node)]));
    }
  }

  // Every node's parent (-1 = none). A node listed as the child of several is an error met when
  // the scene is walked (visitNode); here the first parent wins.
  void findParents() {
    parents_.assign(src_.model.nodes.size(), -1);
    for (size_t i = 0; i < src_.model.nodes.size(); ++i)
      for (int child : src_.model.nodes[i].children)
        if (size_t(child) < parents_.size() && parents_[size_t(child)] < 0)
          parents_[size_t(child)] = int(i);
  }

  // The first perspective camera met in node order becomes the scene camera: at the node's
  // origin, looking down its -Z with its +Y up (glTF 2.0 §3.10.1).
  void addCamera(int index, const glm::mat4& toWorld) {
    const tinygltf::Node& node = src_.model.nodes[size_t(index)];
    if (size_t(node.camera) >= src_.model.cameras.size())
      fail("{}: node {} refers to camera {} ({} cameras)", src_.path, index, node.camera,
           src_.model.cameras.size());
    const tinygltf::Camera& camera = src_.model.cameras[size_t(node.camera)];
    std::string where = gltf::describe("node", index, node.name);
    if (camera.type != "perspective") {
      warnIgnored(src_, "cameras other than perspective ones are ignored", "camera nodes", where);
      return;
    }
    if (scene_.camera) {
      warnIgnored(src_, "cameras after the first perspective one are ignored", "camera nodes",
                  where);
      return;
    }
    double yfov = camera.perspective.yfov;
    if (!(yfov > 0.0 && yfov < glm::pi<double>()))
      fail("{}: camera {} has yfov {}, expected between 0 and pi radians", src_.path, node.camera,
           yfov);
    std::optional<glm::vec3> forward = unitDirection(toWorld, {0.0f, 0.0f, -1.0f});
    std::optional<glm::vec3> up = unitDirection(toWorld, {0.0f, 1.0f, 0.0f});
    if (!forward || !up)
      fail("{}: node {} gives camera {} a degenerate orientation", src_.path, index, node.camera);
    Camera result;
    result.position = glm::vec3(toWorld[3]);
    result.target = result.position + *forward;
    result.up = *up;
    result.verticalFovDegrees = float(glm::degrees(yfov));
    scene_.camera = result;
  }

  // KHR_lights_punctual: the node's {"light": i} places light i at the node origin, shining
  // down the node's -Z.
  void addLight(int index, const glm::mat4& toWorld) {
    const tinygltf::Node& node = src_.model.nodes[size_t(index)];
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.Has("light")) return;
    const tinygltf::Value& ref = ext->second.Get("light");
    double light = ref.IsNumber() ? ref.GetNumberAsDouble() : -1.0;
    if (!(light >= 0.0 && light < double(src_.model.lights.size())) || light != std::floor(light))
      fail("{}: node {} refers to light {} ({} lights)", src_.path, index, light,
           src_.model.lights.size());
    std::optional<PunctualLight> converted = convertLight(size_t(light));
    if (!converted) return;
    converted->position = glm::vec3(toWorld[3]);
    std::optional<glm::vec3> direction = unitDirection(toWorld, {0.0f, 0.0f, -1.0f});
    if (!direction)
      fail("{}: node {} gives light {} a degenerate direction", src_.path, index, light);
    converted->direction = *direction;
    scene_.lights.push_back(*converted);
  }

  std::optional<PunctualLight> convertLight(size_t index) const {
    const tinygltf::Light& l = src_.model.lights[index];
    PunctualLight out;
    if (l.type == "point")
      out.type = PunctualLight::Type::Point;
    else if (l.type == "spot")
      out.type = PunctualLight::Type::Spot;
    else if (l.type == "directional")
      out.type = PunctualLight::Type::Directional;
    else {
      warn(src_, {.group = "lights of unknown type are ignored",
                  .things = "lights",
                  .where = gltf::describe("light", int(index), l.name),
                  .detail = fmt::format("unknown type '{}'; ignored", l.type)});
      return std::nullopt;
    }
    out.name = l.name;
    if (l.color.size() == 3)
      out.color = glm::vec3(float(l.color[0]), float(l.color[1]), float(l.color[2]));
    out.intensity = float(l.intensity);
    out.range = float(l.range);
    out.innerConeAngle = float(l.spot.innerConeAngle);
    out.outerConeAngle = float(l.spot.outerConeAngle);
    bool finite = std::isfinite(out.color.x) && std::isfinite(out.color.y) &&
                  std::isfinite(out.color.z) && std::isfinite(out.intensity) &&
                  std::isfinite(out.range);
    if (!finite || out.intensity < 0.0f || out.range < 0.0f ||
        glm::any(glm::lessThan(out.color, glm::vec3(0.0f))))
      fail("{}: light {} needs finite, non-negative color, intensity and range", src_.path, index);
    if (out.type == PunctualLight::Type::Spot &&
        !(out.innerConeAngle >= 0.0f && out.innerConeAngle < out.outerConeAngle &&
          out.outerConeAngle <= 1.5707964f))
      fail("{}: light {} needs 0 <= innerConeAngle < outerConeAngle <= pi/2, got {} and {}",
           src_.path, index, out.innerConeAngle, out.outerConeAngle);
    return out;
  }

  // Extensions listed in extensionsUsed that Bounce ignores and that no loaded material named
  // already (an unused material's, or one on nodes, textures or meshes).
  void warnUnusedExtensions() {
    for (const std::string& name : src_.model.extensionsUsed) {
      if (gltf::isSupportedExtension(name)) continue;
      std::string group = gltf::ignoredExtensionWarning(name);
      if (src_.warnings.count(group) == 0) warn(src_, {.group = group});
    }
  }

  const Source& src_;
  Scene scene_;
  gltf::MaterialTable materials_;  // refers to scene_, so declared after it
  std::set<int> animatedNodes_;
  std::vector<NodeState> nodeState_;
  gltf::AnimationTargets animationTargets_;
  std::map<int, std::optional<uint32_t>> meshes_;  // glTF mesh -> shared Mesh (not deforming)
  std::map<int, int> skins_;                       // glTF skin -> Scene::skins index
  std::vector<int> parents_;                       // per glTF node
  uint64_t loadedElements_ = 0;
};

Scene loadParsed(const std::string& path, LoadWarnings& warnings) {
  tinygltf::Model model = parseModel(path, warnings);
  checkVersion(path, model);
  checkRequiredExtensions(path, model);
  Source src{model, path, warnings};
  return SceneBuilder(src).build(std::filesystem::path(path).stem().string());
}

}  // namespace

Scene loadGltf(const std::string& path, LoadWarnings& warnings) {
  // Our own checks throw bounce::Error; anything else escaping tinygltf or the standard
  // library (an allocation failure, a length error) still becomes an error naming the file.
  try {
    return loadParsed(path, warnings);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    fail("{}: out of memory while loading", path);
  } catch (const std::exception& e) {
    fail("{}: {}", path, e.what());
  }
}

Scene loadGltf(const std::string& path) {
  LoadWarnings warnings;
  Scene scene = loadGltf(path, warnings);
  warnings.print(stderr, path);
  return scene;
}

}  // namespace bounce
