#include "scene/procedural/mesh_builder.h"

#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

namespace bounce::procedural {

namespace {

constexpr float kPi = 3.14159265358979f;

// Outlines with less area than this are skipped: zero-area triangles are invalid input for the
// renderer, and a skipped sliver (a window touching a wall edge, say) is what was meant anyway.
constexpr float kMinArea = 1e-10f;

uint32_t appendVertex(Geometry& g, const glm::vec3& p, const glm::vec3& n, const glm::vec2& uv) {
  g.positions.push_back(p);
  g.normals.push_back(n);
  g.uvs.push_back(uv);
  return uint32_t(g.positions.size() - 1);
}

void appendTriangle(Geometry& g, uint32_t a, uint32_t b, uint32_t c) {
  g.indices.insert(g.indices.end(), {a, b, c});
}

// Two unit vectors u, v with cross(u, v) = w, so angles measured from u towards v turn
// counter-clockwise seen from the tip of w.
void perpendicularBasis(const glm::vec3& w, glm::vec3& u, glm::vec3& v) {
  glm::vec3 helper = std::abs(w.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  u = glm::normalize(glm::cross(helper, w));
  v = glm::cross(w, u);
}

}  // namespace

// ---- flat faces --------------------------------------------------------------------------------

glm::vec3 newellNormal(const glm::vec3* points, int count) {
  glm::vec3 n{0.0f};
  for (int i = 0; i < count; ++i) {
    const glm::vec3& a = points[i];
    const glm::vec3& b = points[(i + 1) % count];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  float length = glm::length(n);
  return length > 0.0f ? n / length : glm::vec3(0.0f);
}

void addQuad(Geometry& g, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
             const glm::vec3& p3, std::optional<glm::vec2> uvExtent) {
  const glm::vec3 outline[4] = {p0, p1, p2, p3};
  float twiceArea =
      glm::length(glm::cross(p2 - p0, p1 - p0)) + glm::length(glm::cross(p3 - p0, p2 - p0));
  if (twiceArea < 2.0f * kMinArea) return;
  glm::vec3 n = newellNormal(outline, 4);
  glm::vec2 extent = uvExtent ? *uvExtent : glm::vec2(glm::distance(p0, p1), glm::distance(p0, p3));
  uint32_t i0 = appendVertex(g, p0, n, {0.0f, extent.y});
  uint32_t i1 = appendVertex(g, p1, n, {extent.x, extent.y});
  uint32_t i2 = appendVertex(g, p2, n, {extent.x, 0.0f});
  uint32_t i3 = appendVertex(g, p3, n, {0.0f, 0.0f});
  appendTriangle(g, i0, i1, i2);
  appendTriangle(g, i0, i2, i3);
}

void addQuadFacing(Geometry& g, const glm::vec3& front, const glm::vec3& p0, const glm::vec3& p1,
                   const glm::vec3& p2, const glm::vec3& p3) {
  const glm::vec3 outline[4] = {p0, p1, p2, p3};
  if (glm::dot(newellNormal(outline, 4), front) >= 0.0f)
    addQuad(g, p0, p1, p2, p3);
  else
    addQuad(g, p0, p3, p2, p1);
}

void addRect(Geometry& g, const Frame& frame, const glm::vec2& min, const glm::vec2& max) {
  addQuad(g, frame.point(min.x, min.y), frame.point(max.x, min.y), frame.point(max.x, max.y),
          frame.point(min.x, max.y));
}

void addRectWithHole(Geometry& g, const Frame& frame, const glm::vec2& min, const glm::vec2& max,
                     const glm::vec2& holeMin, const glm::vec2& holeMax) {
  addRect(g, frame, min, {holeMin.x, max.y});
  addRect(g, frame, {holeMax.x, min.y}, max);
  addRect(g, frame, {holeMin.x, min.y}, {holeMax.x, holeMin.y});
  addRect(g, frame, {holeMin.x, holeMax.y}, {holeMax.x, max.y});
}

void addOpeningSides(Geometry& g, const Frame& frame, const glm::vec2& holeMin,
                     const glm::vec2& holeMax, float depth) {
  auto corner = [&](float s, float t, float d) { return frame.point(s, t, d); };
  const glm::vec3 up = glm::normalize(frame.up);
  const glm::vec3 right = glm::normalize(frame.right);
  // Each side faces the opposite side across the opening.
  addQuadFacing(g, up, corner(holeMin.x, holeMin.y, 0), corner(holeMax.x, holeMin.y, 0),
                corner(holeMax.x, holeMin.y, depth), corner(holeMin.x, holeMin.y, depth));
  addQuadFacing(g, -up, corner(holeMin.x, holeMax.y, 0), corner(holeMax.x, holeMax.y, 0),
                corner(holeMax.x, holeMax.y, depth), corner(holeMin.x, holeMax.y, depth));
  addQuadFacing(g, right, corner(holeMin.x, holeMin.y, 0), corner(holeMin.x, holeMax.y, 0),
                corner(holeMin.x, holeMax.y, depth), corner(holeMin.x, holeMin.y, depth));
  addQuadFacing(g, -right, corner(holeMax.x, holeMin.y, 0), corner(holeMax.x, holeMax.y, 0),
                corner(holeMax.x, holeMax.y, depth), corner(holeMax.x, holeMin.y, depth));
}

// ---- boxes -------------------------------------------------------------------------------------

void addHexahedron(Geometry& g, const glm::vec3 (&corners)[8], Facing facing, uint32_t faces) {
  glm::vec3 center{0.0f};
  for (const glm::vec3& c : corners) center += c * 0.125f;
  for (int axis = 0; axis < 3; ++axis) {
    // Corner-index bits of the two axes spanning this face, walked as a cycle.
    const uint32_t bitB = 1u << ((axis + 1) % 3);
    const uint32_t bitC = 1u << ((axis + 2) % 3);
    for (uint32_t side = 0; side < 2; ++side) {
      const uint32_t faceBit = 1u << (2 * axis + side);
      if (!(faces & faceBit)) continue;
      const uint32_t base = side << axis;
      const glm::vec3& p0 = corners[base];
      const glm::vec3& p1 = corners[base | bitB];
      const glm::vec3& p2 = corners[base | bitB | bitC];
      const glm::vec3& p3 = corners[base | bitC];
      glm::vec3 outward = 0.25f * (p0 + p1 + p2 + p3) - center;
      addQuadFacing(g, facing == Facing::Outward ? outward : -outward, p0, p1, p2, p3);
    }
  }
}

void addBox(Geometry& g, const Aabb& box, Facing facing, uint32_t faces) {
  glm::vec3 corners[8];
  for (int i = 0; i < 8; ++i)
    corners[i] = {i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                  i & 4 ? box.max.z : box.min.z};
  addHexahedron(g, corners, facing, faces);
}

void addBox(Geometry& g, const glm::mat4& transform, Facing facing, uint32_t faces) {
  glm::vec3 corners[8];
  for (int i = 0; i < 8; ++i) {
    glm::vec3 unit{i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f};
    corners[i] = glm::vec3(transform * glm::vec4(unit, 1.0f));
  }
  addHexahedron(g, corners, facing, faces);
}

// ---- round shapes ------------------------------------------------------------------------------

namespace {

// A flat disc cap as a fan; faces +w if `facingAxis`, else -w.
void addDisc(Geometry& g, const glm::vec3& center, const glm::vec3& u, const glm::vec3& v,
             const glm::vec3& w, float radius, int segments, bool facingAxis) {
  glm::vec3 n = facingAxis ? w : -w;
  uint32_t c = appendVertex(g, center, n, {0.0f, 0.0f});
  uint32_t first = uint32_t(g.positions.size());
  for (int i = 0; i < segments; ++i) {
    float angle = 2.0f * kPi * float(i) / float(segments);
    glm::vec2 local{std::cos(angle), std::sin(angle)};
    appendVertex(g, center + radius * (local.x * u + local.y * v), n, radius * local);
  }
  for (int i = 0; i < segments; ++i) {
    uint32_t a = first + uint32_t(i);
    uint32_t b = first + uint32_t((i + 1) % segments);
    // (c, a, b) winds counter-clockwise around +w because cross(u, v) = w.
    if (facingAxis)
      appendTriangle(g, c, a, b);
    else
      appendTriangle(g, c, b, a);
  }
}

}  // namespace

void addFrustum(Geometry& g, const glm::vec3& base, const glm::vec3& top, float radiusBase,
                float radiusTop, int segments, bool caps) {
  const glm::vec3 axis = top - base;
  const float height = glm::length(axis);
  if (height <= 0.0f || radiusBase <= 0.0f || segments < 3) return;
  const glm::vec3 w = axis / height;
  glm::vec3 u, v;
  perpendicularBasis(w, u, v);
  const bool apex = radiusTop <= 0.0f;
  const float meanRadius = 0.5f * (radiusBase + radiusTop);

  // One column of vertices per segment boundary; the seam is duplicated so uvs can wrap.
  const uint32_t first = uint32_t(g.positions.size());
  for (int i = 0; i <= segments; ++i) {
    float along = float(i) / float(segments);
    float angle = 2.0f * kPi * along;
    glm::vec3 radial = std::cos(angle) * u + std::sin(angle) * v;
    // The side leans inwards by (radiusBase - radiusTop) over its height; its normal leans up.
    glm::vec3 n = glm::normalize(height * radial + (radiusBase - radiusTop) * w);
    float s = along * 2.0f * kPi * meanRadius;
    appendVertex(g, base + radiusBase * radial, n, {s, height});
    // A cone's tip gets one vertex per face, with the normal of that face's middle, so the
    // shading does not pinch to a single direction at the tip.
    float apexAngle = 2.0f * kPi * (float(i) + 0.5f) / float(segments);
    glm::vec3 apexRadial = std::cos(apexAngle) * u + std::sin(apexAngle) * v;
    glm::vec3 topNormal = apex ? glm::normalize(height * apexRadial + radiusBase * w) : n;
    appendVertex(g, top + radiusTop * radial, topNormal, {s, 0.0f});
  }
  for (int i = 0; i < segments; ++i) {
    uint32_t b0 = first + 2u * uint32_t(i), t0 = b0 + 1;
    uint32_t b1 = b0 + 2, t1 = b0 + 3;
    appendTriangle(g, b0, b1, t0);
    if (!apex) appendTriangle(g, b1, t1, t0);
  }
  if (!caps) return;
  addDisc(g, base, u, v, w, radiusBase, segments, false);
  if (!apex) addDisc(g, top, u, v, w, radiusTop, segments, true);
}

void addSphere(Geometry& g, const glm::vec3& center, float radius, int segments, int rings) {
  if (radius <= 0.0f || segments < 3 || rings < 2) return;
  // Rows of vertices from the north pole (ring 0) to the south pole (ring `rings`); the seam
  // column is duplicated so uvs can wrap, and the pole rows hold one vertex per face.
  auto vertex = [&](int ring, float column) {
    float theta = kPi * float(ring) / float(rings);
    float phi = 2.0f * kPi * column / float(segments);
    glm::vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
    return appendVertex(g, center + radius * n, n,
                        {column / float(segments), float(ring) / float(rings)});
  };
  std::vector<uint32_t> rows((rings + 1) * (segments + 1));
  for (int ring = 0; ring <= rings; ++ring)
    for (int column = 0; column <= segments; ++column) {
      bool pole = ring == 0 || ring == rings;
      rows[size_t(ring * (segments + 1) + column)] =
          pole && column == segments ? 0u : vertex(ring, float(column) + (pole ? 0.5f : 0.0f));
    }
  auto at = [&](int ring, int column) { return rows[size_t(ring * (segments + 1) + column)]; };
  // phi grows counter-clockwise seen from +Y and theta downwards, so (ring, column),
  // (ring + 1, column), (ring + 1, column + 1) turns counter-clockwise seen from outside.
  for (int ring = 0; ring < rings; ++ring)
    for (int column = 0; column < segments; ++column) {
      uint32_t a = at(ring, column), b = at(ring + 1, column);
      uint32_t c = at(ring + 1, column + 1), d = at(ring, column + 1);
      if (ring == 0) {
        appendTriangle(g, a, b, c);
      } else if (ring == rings - 1) {
        appendTriangle(g, a, at(rings, column), d);
      } else {
        appendTriangle(g, a, b, c);
        appendTriangle(g, a, c, d);
      }
    }
}

// ---- whole geometries --------------------------------------------------------------------------

void appendTransformed(Geometry& target, const Geometry& source, const glm::mat4& transform) {
  const glm::mat3 linear(transform);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const bool mirrors = glm::determinant(linear) < 0.0f;
  const uint32_t offset = uint32_t(target.positions.size());
  for (size_t i = 0; i < source.positions.size(); ++i) {
    target.positions.push_back(glm::vec3(transform * glm::vec4(source.positions[i], 1.0f)));
    target.normals.push_back(glm::normalize(normalMatrix * source.normals[i]));
    target.uvs.push_back(source.uvs[i]);
  }
  for (size_t t = 0; t + 2 < source.indices.size(); t += 3) {
    uint32_t a = source.indices[t] + offset;
    uint32_t b = source.indices[t + 1] + offset;
    uint32_t c = source.indices[t + 2] + offset;
    if (mirrors)
      appendTriangle(target, a, c, b);
    else
      appendTriangle(target, a, b, c);
  }
}

Geometry& MeshBuilder::geometry(uint32_t material) {
  for (Geometry& g : geometries_)
    if (g.material == material) return g;
  geometries_.emplace_back().material = material;
  return geometries_.back();
}

Mesh MeshBuilder::build(std::string name) {
  Mesh mesh;
  mesh.name = std::move(name);
  for (Geometry& g : geometries_)
    if (!g.indices.empty()) mesh.geometries.push_back(std::move(g));
  geometries_.clear();
  return mesh;
}

// ---- scene helpers -----------------------------------------------------------------------------

Material lambertMaterial(std::string name, const glm::vec3& baseColor) {
  Material m;
  m.name = std::move(name);
  m.baseColor = glm::vec4(baseColor, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

uint32_t addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return uint32_t(scene.materials.size() - 1);
}

uint32_t addMesh(Scene& scene, Mesh mesh) {
  scene.meshes.push_back(std::move(mesh));
  return uint32_t(scene.meshes.size() - 1);
}

void addInstance(Scene& scene, uint32_t mesh, const glm::mat4& transform, std::string name) {
  scene.instances.push_back(Instance{mesh, transform, std::move(name)});
}

uint32_t addMeshInstance(Scene& scene, Mesh mesh) {
  std::string name = mesh.name;
  uint32_t index = addMesh(scene, std::move(mesh));
  addInstance(scene, index, glm::mat4(1.0f), std::move(name));
  return index;
}

Sun sunFromAngles(float elevationDegrees, float azimuthDegrees, float irradiance,
                  const glm::vec3& color) {
  float elevation = glm::radians(elevationDegrees);
  float azimuth = glm::radians(azimuthDegrees);
  Sun sun;
  sun.direction =
      glm::normalize(glm::vec3(std::sin(azimuth) * std::cos(elevation), -std::sin(elevation),
                               std::cos(azimuth) * std::cos(elevation)));
  sun.irradiance = irradiance;
  sun.color = color;
  return sun;
}

glm::mat4 translation(const glm::vec3& offset) {
  return glm::translate(glm::mat4(1.0f), offset);
}

glm::mat4 rotationY(float radians) {
  return glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace bounce::procedural
