// glTF skins (glTF 2.0 §3.7.3) and morph targets (§3.7.2.2) of mesh primitives: the per-vertex
// joint influences, the target deltas, the rest weights and the inverse bind matrices that
// scene/deformation.h poses. The node-level parts (which nodes get a deforming copy of a mesh,
// the skeleton) are in gltf_loader.cpp.
#include <cmath>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "scene/gltf_internal.h"

namespace bounce::gltf {
namespace {

int attributeAccessor(const tinygltf::Primitive& primitive, const std::string& name) {
  auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

bool isUnsignedByteOrShort(int componentType) {
  return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

// JOINTS_0 (unsigned bytes or shorts) or WEIGHTS_0 (floats, or normalized unsigned bytes or
// shorts), the component types glTF 2.0 §3.7.3.3 allows, as one VEC4 per vertex.
std::vector<glm::vec4> readInfluences(const Source& src, const tinygltf::Primitive& primitive,
                                      const char* name, size_t vertexCount,
                                      const std::string& where) {
  int accessor = attributeAccessor(primitive, name);
  if (size_t(accessor) >= src.model.accessors.size())
    fail("{}: {}: {} refers to accessor {} ({} accessors)", src.path, where, name, accessor,
         src.model.accessors.size());
  const tinygltf::Accessor& a = src.model.accessors[size_t(accessor)];
  bool joints = std::strcmp(name, "JOINTS_0") == 0;
  bool allowed = joints ? isUnsignedByteOrShort(a.componentType) && !a.normalized
                        : a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                              (a.normalized && isUnsignedByteOrShort(a.componentType));
  if (!allowed)
    fail("{}: {}: {} has componentType {}{}, expected {}", src.path, where, name, a.componentType,
         a.normalized ? " (normalized)" : "",
         joints ? "UNSIGNED_BYTE or UNSIGNED_SHORT"
                : "FLOAT or normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
  std::vector<float> data =
      readFloatAccessor(src, accessor, TINYGLTF_TYPE_VEC4, fmt::format("{} of {}", name, where));
  if (data.size() / 4 != vertexCount)
    fail("{}: {}: {} has {} elements but POSITION has {}; every attribute needs one per vertex",
         src.path, where, name, data.size() / 4, vertexCount);
  std::vector<glm::vec4> out(vertexCount);
  if (vertexCount > 0) std::memcpy(out.data(), data.data(), data.size() * sizeof(float));
  return out;
}

// One morph target stream (a VEC3 delta per vertex, finite).
std::vector<glm::vec3> readDeltas(const Source& src, int accessor, const std::string& name,
                                  size_t vertexCount, const std::string& where) {
  std::vector<float> data =
      readFloatAccessor(src, accessor, TINYGLTF_TYPE_VEC3, name + " of " + where);
  if (data.size() / 3 != vertexCount)
    fail("{}: {} has {} elements but POSITION has {}", src.path, name + " of " + where,
         data.size() / 3, vertexCount);
  for (size_t i = 0; i < data.size(); ++i)
    if (!std::isfinite(data[i]))
      fail("{}: {} of {}: vertex {} is NaN or infinite", src.path, name, where, i / 3);
  std::vector<glm::vec3> out(vertexCount);
  if (vertexCount > 0) std::memcpy(out.data(), data.data(), data.size() * sizeof(float));
  return out;
}

}  // namespace

bool loadSkinWeights(const Source& src, int mesh, int primitiveIndex, size_t jointCount,
                     Geometry& g) {
  const tinygltf::Primitive& primitive =
      src.model.meshes[size_t(mesh)].primitives[size_t(primitiveIndex)];
  std::string where = describePrimitive(src, mesh, primitiveIndex);
  bool hasJoints = attributeAccessor(primitive, "JOINTS_0") >= 0;
  bool hasWeights = attributeAccessor(primitive, "WEIGHTS_0") >= 0;
  if (!hasJoints && !hasWeights) return false;
  if (hasJoints != hasWeights)
    fail("{}: {} has {} but no {}; a skinned primitive needs both", src.path, where,
         hasJoints ? "JOINTS_0" : "WEIGHTS_0", hasJoints ? "WEIGHTS_0" : "JOINTS_0");
  if (attributeAccessor(primitive, "JOINTS_1") >= 0 ||
      attributeAccessor(primitive, "WEIGHTS_1") >= 0)
    warnIgnored(src,
                "JOINTS_1 and WEIGHTS_1 are ignored: vertices keep their first 4 joint "
                "influences, renormalised",
                "primitives", where);
  size_t n = g.positions.size();
  std::vector<glm::vec4> joints = readInfluences(src, primitive, "JOINTS_0", n, where);
  std::vector<glm::vec4> weights = readInfluences(src, primitive, "WEIGHTS_0", n, where);
  g.joints.resize(n);
  g.weights.resize(n);
  for (size_t v = 0; v < n; ++v) {
    glm::vec4 w = weights[v];
    for (int i = 0; i < 4; ++i)
      if (!std::isfinite(w[i]) || w[i] < 0.0f)
        fail("{}: {}: WEIGHTS_0 of vertex {} has weight {}, expected finite and non-negative",
             src.path, where, v, w[i]);
    // Exporters quantise or truncate influences, so the sum drifts from 1; the spec asks for
    // a linear combination, so it is rescaled rather than rejected.
    float sum = w.x + w.y + w.z + w.w;
    if (!(sum > 0.0f))
      fail("{}: {}: WEIGHTS_0 of vertex {} sums to 0; a skinned vertex needs a joint influence",
           src.path, where, v);
    w /= sum;
    glm::uvec4 j(joints[v]);
    for (int i = 0; i < 4; ++i) {
      if (j[i] < jointCount) continue;
      if (w[i] > 0.0f)
        fail("{}: {}: JOINTS_0 of vertex {} names joint {}, but the skin has {} joints", src.path,
             where, v, j[i], jointCount);
      j[i] = 0;  // an unused slot: any joint in range keeps the GPU's read in bounds
    }
    g.joints[v] = j;
    g.weights[v] = w;
  }
  return true;
}

void loadMorphTargets(const Source& src, int mesh, int primitiveIndex, Geometry& g) {
  const tinygltf::Primitive& primitive =
      src.model.meshes[size_t(mesh)].primitives[size_t(primitiveIndex)];
  std::string where = describePrimitive(src, mesh, primitiveIndex);
  size_t n = g.positions.size();
  g.morphTargets.clear();
  bool ignoredAttribute = false;
  for (size_t k = 0; k < primitive.targets.size(); ++k) {
    MorphTarget target;
    for (const auto& [name, accessor] : primitive.targets[k]) {
      std::string stream = fmt::format("morph target {} {}", k, name);
      if (name == "POSITION")
        target.positions = readDeltas(src, accessor, stream, n, where);
      else if (name == "NORMAL")
        target.normals = readDeltas(src, accessor, stream, n, where);
      else if (name == "TANGENT")
        target.tangents = readDeltas(src, accessor, stream, n, where);
      else
        ignoredAttribute = true;
    }
    g.morphTargets.push_back(std::move(target));
  }
  if (ignoredAttribute)
    warnIgnored(src,
                "morph targets of attributes other than POSITION, NORMAL and TANGENT are ignored",
                "primitives", where);
}

size_t morphTargetCount(const Source& src, int mesh) {
  const tinygltf::Mesh& m = src.model.meshes[size_t(mesh)];
  for (size_t p = 1; p < m.primitives.size(); ++p)
    if (m.primitives[p].targets.size() != m.primitives[0].targets.size())
      fail(
          "{}: {} has {} morph targets but {} has {}; every primitive of a mesh needs the same "
          "number",
          src.path, describePrimitive(src, mesh, 0), m.primitives[0].targets.size(),
          describePrimitive(src, mesh, int(p)), m.primitives[p].targets.size());
  return m.primitives.empty() ? 0 : m.primitives[0].targets.size();
}

std::vector<float> restMorphWeights(const Source& src, int node, size_t targets) {
  const tinygltf::Node& n = src.model.nodes[size_t(node)];
  const tinygltf::Mesh& m = src.model.meshes[size_t(n.mesh)];
  bool fromNode = !n.weights.empty();
  const std::vector<double>& weights = fromNode ? n.weights : m.weights;
  if (weights.empty()) return std::vector<float>(targets, 0.0f);
  std::string owner = fromNode ? describe("node", node, n.name) : describe("mesh", n.mesh, m.name);
  if (weights.size() != targets)
    fail("{}: {} has {} weights for {} morph targets", src.path, owner, weights.size(), targets);
  std::vector<float> out;
  for (double w : weights) {
    if (!std::isfinite(float(w))) fail("{}: {} has a non-finite morph weight", src.path, owner);
    out.push_back(float(w));
  }
  return out;
}

std::vector<glm::mat4> loadInverseBindMatrices(const Source& src, int skin) {
  const tinygltf::Skin& s = src.model.skins[size_t(skin)];
  if (s.inverseBindMatrices < 0) return std::vector<glm::mat4>(s.joints.size(), glm::mat4(1.0f));
  std::string what = describe("skin", skin, s.name);
  std::vector<float> data = readFloatAccessor(src, s.inverseBindMatrices, TINYGLTF_TYPE_MAT4,
                                              "inverseBindMatrices of " + what);
  if (data.size() / 16 != s.joints.size())
    fail("{}: {} has {} inverseBindMatrices for {} joints", src.path, what, data.size() / 16,
         s.joints.size());
  for (float x : data)
    if (!std::isfinite(x)) fail("{}: {} has a non-finite inverse bind matrix", src.path, what);
  std::vector<glm::mat4> out;
  for (size_t j = 0; j < s.joints.size(); ++j)
    out.push_back(glm::make_mat4(data.data() + 16 * j));  // column-major, as glTF
  return out;
}

void bakeTransform(Geometry& g, const glm::mat4& toWorld) {
  glm::mat3 linear(toWorld);
  glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  auto unit = [](const glm::vec3& v, const glm::vec3& fallback) {
    float length = glm::length(v);
    return length > 0.0f && std::isfinite(length) ? v / length : fallback;
  };
  for (glm::vec3& p : g.positions) p = glm::vec3(toWorld * glm::vec4(p, 1.0f));
  for (glm::vec3& n : g.normals) n = unit(normalMatrix * n, n);
  for (glm::vec4& t : g.tangents) t = glm::vec4(unit(linear * glm::vec3(t), glm::vec3(t)), t.w);
  for (MorphTarget& target : g.morphTargets) {
    for (glm::vec3& d : target.positions) d = linear * d;
    for (glm::vec3& d : target.normals) d = normalMatrix * d;
    for (glm::vec3& d : target.tangents) d = linear * d;
  }
}

}  // namespace bounce::gltf
