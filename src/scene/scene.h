// The scene model every part of Bounce shares: meshes made of geometries (glTF primitives),
// instances placing meshes in the world, glTF metallic-roughness materials, images, punctual
// lights, a camera, and the sun and sky. Conventions: glTF space, +Y up, metres, right-handed;
// colours are linear RGB.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/animation.h"

namespace bounce {

struct Aabb {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  bool empty() const { return min.x > max.x; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
};

// One morph target of a geometry (glTF 2.0 §3.7.2.2): displacements added to the rest streams,
// each scaled by the mesh's current weight of this target. Each stream is empty (the target does
// not move it) or one entry per position.
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;  // xyz only; the handedness (w) does not morph
};

// One triangle list with one material (a glTF mesh primitive). After loading, every stream is
// filled: `normals` and `uvs` have one entry per position (defaults are computed or zero when a
// file lacks them); `tangents` and `colors` are either empty or one per position.
struct Geometry {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec4> tangents;  // xyz tangent, w = bitangent sign
  // glTF COLOR_0, linear RGBA in [0, 1]: multiplies the material's base colour and alpha
  // (glTF 2.0 §3.9.2). Empty = white.
  std::vector<glm::vec4> colors;
  std::vector<uint32_t> indices;  // three per triangle
  uint32_t material = 0;
  // Skinning (glTF JOINTS_0, WEIGHTS_0) of a geometry of a skinned mesh: one entry per position,
  // else both empty. Joint indices index the mesh's skin's `joints`; the four weights sum to 1.
  std::vector<glm::uvec4> joints;
  std::vector<glm::vec4> weights;
  // As many as the mesh's morphWeights (every geometry of a mesh has the same target count).
  std::vector<MorphTarget> morphTargets;
  uint32_t triangleCount() const { return uint32_t(indices.size() / 3); }
};

// A mesh's positions may deform over time (scene/deformation.h): morph targets blend with
// `morphWeights`, then a skin places every vertex by its joints. A deforming mesh is placed by
// one instance only (the glTF loader gives each skinned or morphed node its own copy), since its
// posed triangles are its own. The instance of a skinned mesh has the identity transform: the
// skin's joint matrices place the vertices in the world (glTF 2.0 §3.7.3.1 ignores the skinned
// node's own transform).
struct Mesh {
  std::string name;
  std::vector<Geometry> geometries;
  int skin = -1;                    // Scene::skins index; -1 = not skinned
  std::vector<float> morphWeights;  // rest weights, one per morph target; empty = no targets
  bool deforms() const { return skin >= 0 || !morphWeights.empty(); }
};

// A node of the hierarchy that skins and instances hang from (a glTF node that is a joint, the
// parent of a mesh node below an animated node, or an ancestor of one). Parents come before
// their children. `local` is the rest transform relative to the
// parent (to the world for a root); SceneAnimation::joints may animate it.
struct SkeletonNode {
  std::string name;
  int parent = -1;  // Scene::skeleton index; -1 = a root
  glm::mat4 local{1.0f};
};

// glTF skin (§3.7.3): the vertex influence of joint j is skeletonWorld(joints[j]) x
// inverseBindMatrices[j] applied to the (morphed) rest position.
struct Skin {
  std::string name;
  std::vector<uint32_t> joints;                // Scene::skeleton indices
  std::vector<glm::mat4> inverseBindMatrices;  // one per joint
};

struct Instance {
  uint32_t mesh = 0;
  glm::mat4 transform{1.0f};  // object to world
  std::string name;
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness material. Texture fields index Scene::images, -1 = none.
struct Material {
  std::string name;
  glm::vec4 baseColor{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};  // emissiveFactor x KHR_materials_emissive_strength
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  int baseColorTexture = -1;          // sRGB RGBA
  int metallicRoughnessTexture = -1;  // linear; G = roughness, B = metallic
  int normalTexture = -1;             // linear tangent-space normal
  int emissiveTexture = -1;           // sRGB RGB
};

// Decoded 8-bit RGBA pixels, rows top to bottom. Whether they are sRGB-encoded depends on how a
// material uses them, not on the image.
struct Image {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;
};

// KHR_lights_punctual. Point and spot intensity in candela (lm/sr), directional in lux.
struct PunctualLight {
  enum class Type { Point, Spot, Directional };
  Type type = Type::Point;
  std::string name;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0 = infinite
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.7853982f;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // direction the light travels (spot, directional)
};

// A pinhole camera: position, the point it looks at, vertical field of view in degrees.
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovDegrees = 45.0f;
};

// The sun: `direction` is the direction the light travels (towards the ground), `irradiance`
// the irradiance E in W/m^2 on a surface facing the sun, so a white Lambert surface facing it
// has radiance E / pi. irradiance 0 = no sun.
struct Sun {
  glm::vec3 direction{0.3f, -1.0f, 0.2f};
  float irradiance = 0.0f;
  glm::vec3 color{1.0f};
  float angularDiameterDegrees = 0.53f;
};

enum class SkyModel { Constant, Daylight };

// What rays that leave the scene see. Constant: `radiance` in every direction. Daylight: the
// analytic clear sky of Preetham, Shirley & Smits 1999 (shaders/common/sky.glsl) for the sun's
// direction and `turbidity` (2 very clear, 3 clear, 6 hazy, 10 thin overcast; the model's
// range). The model gives luminance in kcd/m^2; Bounce scales it by daylightSkyScale(sun) so that
// sun and sky keep their natural ratio in whatever units the sun's irradiance E is given: E
// stands for a clear day's direct-normal illuminance of kDaylightSunKilolux. Without a sun
// (E = 0) the daylight sky is black; it fades out as the sun sets.
struct Sky {
  SkyModel model = SkyModel::Constant;
  glm::vec3 radiance{0.0f};
  float turbidity = 3.0f;
};

inline constexpr float kDaylightSunKilolux = 100.0f;
inline float daylightSkyScale(const Sun& sun) {
  return sun.irradiance / kDaylightSunKilolux;
}

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;  // never empty after loading: a default grey one if needed
  std::vector<Image> images;
  std::vector<PunctualLight> lights;
  // Joints of the skins, nodes that instances hang under (TransformTrack::parentNode), and
  // their ancestors.
  std::vector<SkeletonNode> skeleton;
  std::vector<Skin> skins;
  std::optional<Camera> camera;  // from the file or the procedural scene; else a default framing
  Sun sun;
  Sky sky;
  // What moves over time (glTF animations, a built-in scene's scripted motion and default
  // camera path); empty for a still scene. Played by `bounce render --animate`.
  SceneAnimation animation;

  Aabb bounds() const;
  uint64_t triangleCount() const;        // over instances, i.e. what a ray can hit
  uint64_t uniqueTriangleCount() const;  // over meshes
  bool deforms() const;                  // some mesh has a skin or morph targets
};

// A camera that frames the scene's bounds from the front (+Z side), slightly above.
Camera defaultCamera(const Scene& scene);

// Checks invariants every consumer relies on (indices in range, streams sized, materials and
// textures referenced exist, finite positions). Throws bounce::Error naming `source` and the
// problem. Loaders and procedural builders call it before returning.
void validateScene(const Scene& scene, const std::string& source);

}  // namespace bounce
