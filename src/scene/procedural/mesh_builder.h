// Building blocks for the built-in procedural scenes: quads, boxes, walls with openings,
// cylinders and cones appended to a Geometry, plus small helpers that add materials, meshes,
// instances and the sun to a Scene.
//
// Conventions (glTF): +Y up, metres, counter-clockwise front faces. Every primitive fills
// positions, normals and uvs for every vertex, and its normals agree with its winding. Flat
// faces get the Newell normal of their outline (what Blender exports for a quad, also for
// slightly non-planar ones); curved sides get smooth normals. Unless given explicitly, uvs are
// in metres along the face, so tiling textures keep their scale on faces of any size.
#pragma once
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce::procedural {

// ---- flat faces --------------------------------------------------------------------------------

// Appends quad p0 p1 p2 p3, counter-clockwise seen from its front (p0 bottom-left, p1
// bottom-right, p2 top-right, p3 top-left), as triangles (p0 p1 p2) and (p0 p2 p3). uvExtent
// sets the uv of p2 with v pointing down the image (glTF): p0 = (0, extent.y), p2 = (extent.x, 0).
void addQuad(Geometry& g, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
             const glm::vec3& p3, std::optional<glm::vec2> uvExtent = std::nullopt);

// Like addQuad, but reverses the winding if needed so that the quad faces `front`. Saves
// working out the corner order by hand for faces built from coordinates.
void addQuadFacing(Geometry& g, const glm::vec3& front, const glm::vec3& p0, const glm::vec3& p1,
                   const glm::vec3& p2, const glm::vec3& p3);

// Unit Newell normal of a polygon outline (zero for a degenerate outline).
glm::vec3 newellNormal(const glm::vec3* points, int count);

// A plane with 2D coordinates: point(s, t) = origin + s * right + t * up. Faces built in a frame
// look along front() = cross(right, up); `depth` goes behind the face, against front().
struct Frame {
  glm::vec3 origin{0.0f};
  glm::vec3 right{1.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};

  glm::vec3 front() const { return glm::normalize(glm::cross(right, up)); }
  glm::vec3 point(float s, float t, float depth = 0.0f) const {
    return origin + s * right + t * up - depth * front();
  }
};

// The rectangle [min, max] of a frame, facing front().
void addRect(Geometry& g, const Frame& frame, const glm::vec2& min, const glm::vec2& max);

// The rectangle [min, max] with the rectangular hole [holeMin, holeMax] cut out (which must lie
// strictly inside), as four quads: full-height strips left and right of the hole, and pieces
// below and above it.
void addRectWithHole(Geometry& g, const Frame& frame, const glm::vec2& min, const glm::vec2& max,
                     const glm::vec2& holeMin, const glm::vec2& holeMax);

// The four faces lining a rectangular opening [holeMin, holeMax] that goes `depth` deep behind
// the frame's plane (window reveals), facing into the opening.
void addOpeningSides(Geometry& g, const Frame& frame, const glm::vec2& holeMin,
                     const glm::vec2& holeMax, float depth);

// ---- boxes -------------------------------------------------------------------------------------

enum class Facing { Outward, Inward };

// Faces of a box, as bits, named by the axis direction they face when the box faces outward.
enum BoxFace : uint32_t {
  kFaceNegX = 1u << 0,
  kFacePosX = 1u << 1,
  kFaceNegY = 1u << 2,
  kFacePosY = 1u << 3,
  kFaceNegZ = 1u << 4,
  kFacePosZ = 1u << 5,
  kAllFaces = 63u,
  kNoBottom = kAllFaces & ~kFaceNegY,  // boxes standing on something: the bottom is never seen
};

// A hexahedron from 8 corners indexed by bits (x | y << 1 | z << 2) of the unit cube it deforms;
// faces get their own vertices so edges stay sharp. Inward facing turns the box into a room.
void addHexahedron(Geometry& g, const glm::vec3 (&corners)[8], Facing facing = Facing::Outward,
                   uint32_t faces = kAllFaces);
void addBox(Geometry& g, const Aabb& box, Facing facing = Facing::Outward,
            uint32_t faces = kAllFaces);
// The unit cube [-0.5, 0.5]^3 under `transform` (rotated, scaled, sheared boxes).
void addBox(Geometry& g, const glm::mat4& transform, Facing facing = Facing::Outward,
            uint32_t faces = kAllFaces);

// ---- round shapes ------------------------------------------------------------------------------

// A truncated cone from `base` to `top` with smooth side normals and optional flat caps;
// radiusTop = 0 makes a cone, equal radii a cylinder.
void addFrustum(Geometry& g, const glm::vec3& base, const glm::vec3& top, float radiusBase,
                float radiusTop, int segments, bool caps = true);
inline void addCylinder(Geometry& g, const glm::vec3& base, const glm::vec3& top, float radius,
                        int segments, bool caps = true) {
  addFrustum(g, base, top, radius, radius, segments, caps);
}
inline void addCone(Geometry& g, const glm::vec3& base, const glm::vec3& apex, float radius,
                    int segments, bool cap = true) {
  addFrustum(g, base, apex, radius, 0.0f, segments, cap);
}
// A UV sphere with smooth (exactly radial) normals: `segments` around the vertical axis,
// `rings` from pole to pole. Each pole is a fan of triangles with one vertex per face, so uvs
// wrap without zero-area triangles. u runs around (0..1), v from the north pole down (0..1).
void addSphere(Geometry& g, const glm::vec3& center, float radius, int segments, int rings);

// ---- whole geometries --------------------------------------------------------------------------

// Appends `source` transformed by `transform` (normals by its inverse transpose; a mirroring
// transform also flips the winding so front faces stay front faces).
void appendTransformed(Geometry& target, const Geometry& source, const glm::mat4& transform);

// Collects triangles per material while a mesh is built, then hands them over as a Mesh with one
// geometry per material used.
class MeshBuilder {
 public:
  // The triangle list for `material`, created on first use. References stay valid until build(),
  // so code can hold several at once.
  Geometry& geometry(uint32_t material);
  Mesh build(std::string name);

 private:
  std::deque<Geometry> geometries_;
};

// ---- scene helpers -----------------------------------------------------------------------------

// A pure Lambert material: metallic 0, roughness 1.
Material lambertMaterial(std::string name, const glm::vec3& baseColor);
uint32_t addMaterial(Scene& scene, Material material);
uint32_t addMesh(Scene& scene, Mesh mesh);
void addInstance(Scene& scene, uint32_t mesh, const glm::mat4& transform, std::string name);
// Adds the mesh and one instance of it at the identity, both under the mesh's name.
uint32_t addMeshInstance(Scene& scene, Mesh mesh);

// The sun at `elevationDegrees` above the horizon, shining from azimuth `azimuthDegrees`
// (0 = from -Z, 90 = from -X, i.e. light travelling towards +Z / +X).
Sun sunFromAngles(float elevationDegrees, float azimuthDegrees, float irradiance,
                  const glm::vec3& color);

glm::mat4 translation(const glm::vec3& offset);
glm::mat4 rotationY(float radians);

}  // namespace bounce::procedural
