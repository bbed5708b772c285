// glTF mesh primitives -> Geometry: attribute streams, topology, index checks, degenerate
// triangles, and the defaults the scene model promises (normals and UVs always present).
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "scene/gltf_internal.h"

namespace bounce::gltf {
namespace {

int attributeAccessor(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

// Dense floats from readFloatAccessor -> glm vectors of the same component count.
template <typename Vec>
std::vector<Vec> toVectors(const std::vector<float>& floats) {
  std::vector<Vec> out(floats.size() / Vec::length());
  if (!out.empty()) std::memcpy(out.data(), floats.data(), out.size() * sizeof(Vec));
  return out;
}

// Reads attribute `name` as `expectedType` and checks it has one element per vertex.
std::vector<float> readAttribute(const Source& src, const tinygltf::Primitive& primitive,
                                 const char* name, int expectedType, size_t vertexCount,
                                 const std::string& where) {
  int accessor = attributeAccessor(primitive, name);
  if (accessor < 0) return {};
  std::vector<float> data =
      readFloatAccessor(src, accessor, expectedType, fmt::format("{} of {}", name, where));
  size_t components = expectedType == TINYGLTF_TYPE_VEC2   ? 2
                      : expectedType == TINYGLTF_TYPE_VEC3 ? 3
                                                           : 4;
  if (data.size() / components != vertexCount)
    fail("{}: {}: {} has {} elements but POSITION has {}; every attribute needs one per vertex",
         src.path, where, name, data.size() / components, vertexCount);
  return data;
}

// COLOR_0 as linear RGBA (glTF 2.0 §3.7.2.1): VEC3 (alpha 1) or VEC4, of floats or of
// normalized unsigned bytes or shorts, which readFloatAccessor maps to [0, 1]. Floats outside
// [0, 1] are clamped (the spec's range for colours), non-finite ones become 1 (no tint).
std::vector<glm::vec4> readVertexColors(const Source& src, const tinygltf::Primitive& primitive,
                                        size_t vertexCount, const std::string& where) {
  int accessor = attributeAccessor(primitive, "COLOR_0");
  if (accessor < 0) return {};
  if (size_t(accessor) >= src.model.accessors.size())
    fail("{}: {}: COLOR_0 refers to accessor {} ({} accessors)", src.path, where, accessor,
         src.model.accessors.size());
  const tinygltf::Accessor& a = src.model.accessors[size_t(accessor)];
  bool floats = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool normalizedInts = a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!floats && !normalizedInts)
    fail(
        "{}: {}: COLOR_0 has componentType {}{}, expected FLOAT or normalized UNSIGNED_BYTE or "
        "UNSIGNED_SHORT",
        src.path, where, a.componentType, a.normalized ? " (normalized)" : "");
  // Anything but VEC3 is read as VEC4, whose type check names the accessor's real type.
  int type = a.type == TINYGLTF_TYPE_VEC3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
  std::vector<float> data = readAttribute(src, primitive, "COLOR_0", type, vertexCount, where);
  size_t components = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
  std::vector<glm::vec4> colors(vertexCount, glm::vec4(1.0f));
  for (size_t v = 0; v < vertexCount; ++v)
    for (size_t c = 0; c < components; ++c) {
      float x = data[v * components + c];
      colors[v][int(c)] = std::isfinite(x) ? glm::clamp(x, 0.0f, 1.0f) : 1.0f;
    }
  return colors;
}

// Strips and fans become lists with the winding the spec defines (glTF 2.0 §3.7.2.1), so
// front faces stay front faces.
std::vector<uint32_t> triangleListIndices(const std::vector<uint32_t>& indices, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
  std::vector<uint32_t> list;
  size_t triangles = indices.size() < 3 ? 0 : indices.size() - 2;
  list.reserve(triangles * 3);
  for (size_t i = 0; i < triangles; ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      bool odd = i % 2 == 1;
      list.insert(list.end(), {indices[i], indices[i + (odd ? 2 : 1)], indices[i + (odd ? 1 : 2)]});
    } else {  // fan
      list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
    }
  }
  return list;
}

void checkIndexRange(const Source& src, const std::vector<uint32_t>& indices, size_t vertexCount,
                     const std::string& where) {
  for (uint32_t index : indices)
    if (index >= vertexCount)
      fail("{}: {}: index {} out of range ({} vertices)", src.path, where, index, vertexCount);
}

void checkFinitePositions(const Source& src, const std::vector<float>& positions,
                          const std::string& where) {
  for (size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i]))
      fail("{}: {}: POSITION of vertex {} is NaN or infinite", src.path, where, i / 3);
}

glm::vec3 faceNormalTimesTwiceArea(const std::vector<glm::vec3>& p, const uint32_t* tri) {
  return glm::cross(p[tri[1]] - p[tri[0]], p[tri[2]] - p[tri[0]]);
}

// A triangle is dropped when its cross product is exactly zero in float: repeated indices,
// coincident or exactly collinear vertices. Such triangles have no normal, break watertight
// ray tests' tie rules and divide by zero in area sampling of emitters. Thin but valid slivers
// are kept.
size_t removeZeroAreaTriangles(const std::vector<glm::vec3>& positions,
                               std::vector<uint32_t>& indices) {
  size_t kept = 0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (faceNormalTimesTwiceArea(positions, &indices[t]) == glm::vec3(0.0f)) continue;
    for (int k = 0; k < 3; ++k) indices[kept + k] = indices[t + k];
    kept += 3;
  }
  size_t removed = (indices.size() - kept) / 3;
  indices.resize(kept);
  return removed;
}

// Area-weighted vertex normals: the unnormalised cross product of each triangle already
// carries twice its area, so large faces dominate shared vertices. Vertices no triangle uses
// get +Y so the stream stays unit length.
std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices) {
  std::vector<glm::vec3> sum(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::vec3 n = faceNormalTimesTwiceArea(positions, &indices[t]);
    for (int k = 0; k < 3; ++k) sum[indices[t + k]] += n;
  }
  for (glm::vec3& n : sum) {
    float length = glm::length(n);
    n = std::isfinite(length) && length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return sum;
}

bool isUsableDirection(const glm::vec3& v) {
  float length = glm::length(v);
  return std::isfinite(length) && length > 1e-20f;
}

// File normals are normalised (quantised or sloppy exporters give non-unit ones); unusable
// ones (zero, NaN) are replaced by computed smooth normals so NaN never reaches shading.
void fillNormals(const Source& src, Geometry& g, std::vector<glm::vec3> fileNormals,
                 const std::string& where) {
  if (fileNormals.empty()) {
    g.normals = smoothNormals(g.positions, g.indices);
    return;
  }
  size_t repaired = 0;
  std::vector<glm::vec3> computed;
  for (size_t i = 0; i < fileNormals.size(); ++i) {
    if (isUsableDirection(fileNormals[i])) {
      fileNormals[i] = glm::normalize(fileNormals[i]);
      continue;
    }
    if (computed.empty()) computed = smoothNormals(g.positions, g.indices);
    fileNormals[i] = computed[i];
    ++repaired;
  }
  if (repaired > 0)
    warn(src, {.group = "replaced zero or non-finite normals by computed ones",
               .things = "primitives",
               .where = where,
               .detail = fmt::format("replaced {} zero or non-finite normals", repaired),
               .amount = repaired,
               .unit = "normals"});
  g.normals = std::move(fileNormals);
}

void fillUvs(const Source& src, Geometry& g, std::vector<glm::vec2> fileUvs,
             const std::string& where) {
  if (fileUvs.empty()) {
    g.uvs.assign(g.positions.size(), glm::vec2(0.0f));
    return;
  }
  size_t repaired = 0;
  for (glm::vec2& uv : fileUvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
      uv = glm::vec2(0.0f);
      ++repaired;
    }
  if (repaired > 0)
    warn(src, {.group = "replaced non-finite UVs by 0",
               .things = "primitives",
               .where = where,
               .detail = fmt::format("replaced {} non-finite UVs by 0", repaired),
               .amount = repaired,
               .unit = "UVs"});
  g.uvs = std::move(fileUvs);
}

// Tangents are optional in the scene model, so a stream with any unusable entry is dropped
// as a whole (consumers then derive tangents themselves) rather than patched. w is snapped
// to +-1 because it is only a handedness sign.
void fillTangents(const Source& src, Geometry& g, std::vector<glm::vec4> fileTangents,
                  const std::string& where) {
  for (glm::vec4& t : fileTangents) {
    if (!isUsableDirection(glm::vec3(t)) || !std::isfinite(t.w)) {
      warn(src, {.group = "TANGENT has zero or non-finite entries; tangents dropped",
                 .things = "primitives",
                 .where = where});
      return;
    }
    t = glm::vec4(glm::normalize(glm::vec3(t)), t.w < 0.0f ? -1.0f : 1.0f);
  }
  g.tangents = std::move(fileTangents);
}

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "points";
    case TINYGLTF_MODE_LINE:
      return "lines";
    case TINYGLTF_MODE_LINE_LOOP:
      return "line loop";
    case TINYGLTF_MODE_LINE_STRIP:
      return "line strip";
    default:
      return "unknown";
  }
}

bool isTriangleMode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

std::vector<uint32_t> readTriangleIndices(const Source& src, const tinygltf::Primitive& primitive,
                                          int mode, size_t vertexCount, const std::string& where) {
  std::vector<uint32_t> indices;
  if (primitive.indices >= 0) {
    indices = readIndexAccessor(src, primitive.indices, "indices of " + where);
  } else {
    indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) indices[i] = uint32_t(i);
  }
  if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
    fail("{}: {}: {} {} is not a multiple of 3 for a triangle list", src.path, where,
         primitive.indices >= 0 ? "index count" : "vertex count", indices.size());
  checkIndexRange(src, indices, vertexCount, where);
  return triangleListIndices(indices, mode);
}

// Drops zero-area triangles with a warning; false, after a warning, when none is left (the
// primitive is then skipped: a valid file may hold degenerate geometry, and it renders as if
// that primitive were not there).
bool dropZeroAreaTriangles(const Source& src, Geometry& g, const std::string& where) {
  size_t before = g.indices.size() / 3;
  size_t removed = removeZeroAreaTriangles(g.positions, g.indices);
  if (removed == 0) return true;
  if (removed == before) {
    warn(src,
         {.group = "skipped: every triangle has zero area",
          .things = "primitives",
          .where = where,
          .detail = before == 1 ? std::string("skipped: its one triangle has zero area")
                                : fmt::format("skipped: all {} triangles have zero area", before),
          .amount = before,
          .unit = "triangles"});
    return false;
  }
  warn(src, {.group = "dropped zero-area triangles",
             .things = "primitives",
             .where = where,
             .detail = fmt::format("dropped {} of {} triangles with zero area", removed, before),
             .amount = removed,
             .unit = "triangles"});
  return true;
}

}  // namespace

std::string describe(const char* kind, int index, const std::string& name) {
  return name.empty() ? fmt::format("{} {}", kind, index)
                      : fmt::format("{} {} ('{}')", kind, index, name);
}

std::string describePrimitive(const Source& src, int mesh, int primitive) {
  return fmt::format("{} primitive {}", describe("mesh", mesh, src.model.meshes[size_t(mesh)].name),
                     primitive);
}

std::optional<Geometry> loadPrimitive(const Source& src, int meshIndex, int primitiveIndex) {
  const tinygltf::Primitive& primitive =
      src.model.meshes[size_t(meshIndex)].primitives[size_t(primitiveIndex)];
  std::string where = describePrimitive(src, meshIndex, primitiveIndex);
  int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (!isTriangleMode(mode)) {
    warn(src,
         {.group = "skipped: points and lines are not rendered",
          .things = "primitives",
          .where = where,
          .detail = fmt::format("skipped: mode {} ({}) is not triangles", mode, modeName(mode))});
    return std::nullopt;
  }
  int positionAccessor = attributeAccessor(primitive, "POSITION");
  if (positionAccessor < 0) fail("{}: {} has no POSITION attribute", src.path, where);
  std::vector<float> positions =
      readFloatAccessor(src, positionAccessor, TINYGLTF_TYPE_VEC3, "POSITION of " + where);
  checkFinitePositions(src, positions, where);
  size_t vertexCount = positions.size() / 3;

  Geometry g;
  g.positions = toVectors<glm::vec3>(positions);
  g.indices = readTriangleIndices(src, primitive, mode, vertexCount, where);
  if (g.indices.empty()) {
    warn(src, {.group = "skipped: no triangles", .things = "primitives", .where = where});
    return std::nullopt;
  }
  if (!dropZeroAreaTriangles(src, g, where)) return std::nullopt;
  fillNormals(src, g,
              toVectors<glm::vec3>(
                  readAttribute(src, primitive, "NORMAL", TINYGLTF_TYPE_VEC3, vertexCount, where)),
              where);
  fillUvs(src, g,
          toVectors<glm::vec2>(
              readAttribute(src, primitive, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, vertexCount, where)),
          where);
  fillTangents(src, g,
               toVectors<glm::vec4>(readAttribute(src, primitive, "TANGENT", TINYGLTF_TYPE_VEC4,
                                                  vertexCount, where)),
               where);
  g.colors = readVertexColors(src, primitive, vertexCount, where);
  return g;
}

void transformUvs(Geometry& geometry, const glm::mat3& uvTransform) {
  for (glm::vec2& uv : geometry.uvs) uv = glm::vec2(uvTransform * glm::vec3(uv, 1.0f));
}

}  // namespace bounce::gltf
