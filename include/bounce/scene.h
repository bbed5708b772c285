// What Bounce renders: triangle meshes with glTF metallic-roughness materials placed by
// instances, emissive surfaces, a sun and a sky. Load one (a built-in procedural scene by name,
// or a glTF 2.0 file) or build it in code; both can be mixed (meshes added to a loaded scene).
// Conventions: glTF space (+Y up, metres, right-handed, counter-clockwise front faces);
// colours are linear RGB; light in W/m^2 (irradiance) and W/(m^2 sr) (radiance).
//
//   bounce::Scene scene;
//   bounce::MaterialId white = scene.addMaterial({.baseColor = {0.8f, 0.8f, 0.8f}});
//   bounce::MeshId quad = scene.addMesh(positions, normals, indices, white);
//   scene.addInstance(quad, bounce::Mat4::translation({0.0f, 1.0f, 0.0f}));
//   scene.setSun({.direction = {0.3f, -1.0f, 0.2f}, .irradiance = 100.0f});
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bounce/camera.h"
#include "bounce/config.h"
#include "bounce/math.h"

namespace bounce::api {

// glTF 2.0 metallic-roughness, without textures (a loaded glTF file keeps its textures).
struct Material {
  Vec3 baseColor{0.8f, 0.8f, 0.8f};  // albedo of a dielectric, specular colour of a metal; [0, 1]
  float roughness = 0.5f;            // perceptual roughness in [0, 1]; 0 = mirror
  float metallic = 0.0f;             // 0 = dielectric, 1 = metal
  // Emitted radiance, W/(m^2 sr) per channel; zero for a surface that does not glow. Emissive
  // triangles light the scene (direct light sampling and GI).
  Vec3 emission{0.0f, 0.0f, 0.0f};
  // Whether the back face is the same surface (a thin sheet) or not drawn (a closed solid).
  bool doubleSided = false;
};

struct MaterialId {
  uint32_t index = 0;
};
struct MeshId {
  uint32_t index = 0;
};

// The sun: `direction` is the direction the light travels (towards the ground, need not be
// unit length); `irradiance` is E in W/m^2 on a surface facing the sun, so that a white Lambert
// surface facing it has radiance E / pi. irradiance 0 = no sun.
struct Sun {
  Vec3 direction{0.3f, -1.0f, 0.2f};
  float irradiance = 0.0f;
  Vec3 color{1.0f, 1.0f, 1.0f};          // multiplies the irradiance
  float angularDiameterDegrees = 0.53f;  // softness of its shadows
};

// What rays that leave the scene see. Constant: `radiance` in every direction (W/(m^2 sr)).
// Daylight: the analytic clear sky of Preetham, Shirley & Smits 1999 for the sun's direction and
// `turbidity` in [2, 10] (2 very clear, 3 clear, 6 hazy, 10 thin overcast), scaled to the sun's
// irradiance; black without a sun.
struct Sky {
  enum class Model { Constant, Daylight };
  Model model = Model::Constant;
  Vec3 radiance{0.0f, 0.0f, 0.0f};
  float turbidity = 3.0f;
};

class Scene {
 public:
  // An empty scene: no geometry, no sun, a black sky. Copies are deep; a moved-from Scene may
  // only be assigned to or destroyed.
  Scene();
  ~Scene();
  Scene(const Scene& other);
  Scene(Scene&& other) noexcept;
  Scene& operator=(const Scene& other);
  Scene& operator=(Scene&& other) noexcept;

  // A built-in scene by name (builtinNames()), or a glTF 2.0 file (a path ending in .gltf or
  // .glb). Throws bounce::Error naming the path and the problem (missing file, malformed glTF,
  // unknown name); prints what it ignores or repairs in the file to stderr, one line per kind
  // of problem. A file without any light (no lights, no emissive material) gets a daylight
  // sun and sky at mid-morning, as glTF viewers do; setSun / setSky replace them.
  static Scene load(const std::string& nameOrPath);
  // cornell, sunroom, sunroom-glossy, foliage, manylights, furnace, city, city-10k, spheres
  // (docs/scenes.md describes each).
  static std::vector<std::string> builtinNames();

  MaterialId addMaterial(const Material& material);
  // One triangle list with one material. `normals`: one unit normal per position, or empty for
  // area-weighted smooth normals; `indices`: three per triangle. Throws bounce::Error for
  // indices out of range, a count not a multiple of 3, non-finite positions, a normal count
  // that matches neither, or an unknown material.
  MeshId addMesh(std::span<const Vec3> positions, std::span<const Vec3> normals,
                 std::span<const uint32_t> indices, MaterialId material);
  // Places a mesh in the world (objectToWorld). A mesh without instances is not rendered.
  void addInstance(MeshId mesh, const Mat4& objectToWorld = {});

  void setSun(const Sun& sun);
  void setSky(const Sky& sky);
  Sun sun() const;
  Sky sky() const;
  // The scene's own camera (the glTF file's, or the built-in scene's), else one that frames its
  // bounds from the +Z side, slightly above.
  Camera camera() const;

  std::string name() const;  // the built-in name or the file's; empty for a scene built in code
  uint64_t triangleCount() const;  // over instances, i.e. what a ray can hit

 private:
  friend class Renderer;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce::api
