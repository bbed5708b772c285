// The scene test_motion.cpp and test_taa.cpp share, without its lighting: a floor with a smooth
// wave texture (so a wrong reprojection shows, and a right one survives bilinear resampling) and
// a 1 m card facing the camera (instance 1, which may move). Material 0 is `grey` (double-sided,
// the card), material 1 the floor's white textured copy of it; a sun of irradiance 3.
#pragma once
#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"

namespace bounce::test {

inline Scene floorAndCardUnlit(const glm::vec4& grey) {
  Scene scene;
  scene.name = "floor-and-card";
  auto quad = [](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
    Geometry g;
    g.positions = {a, b, c, d};
    g.normals.assign(4, n);
    g.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    g.indices = {0, 1, 2, 0, 2, 3};
    return g;
  };
  Geometry floor = quad({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {0, 1, 0});
  floor.uvs = {{0, 0}, {0, 3}, {3, 3}, {3, 0}};
  floor.material = 1;
  scene.meshes.push_back({"floor", {floor}});
  Image waves{"waves", 64, 64, {}};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      float v = 0.5f + 0.2f * std::sin(float(M_PI) * x / 16.0f) +
                0.2f * std::cos(float(M_PI) * y / 16.0f);
      uint8_t c = uint8_t(255.0f * v);
      waves.rgba.insert(waves.rgba.end(), {c, uint8_t(255 - c), 128, 255});
    }
  scene.images.push_back(waves);
  scene.meshes.push_back(
      {"card", {quad({-0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f, 1, 0}, {-0.5f, 1, 0}, {0, 0, 1})}});
  scene.instances.push_back({0, glm::mat4(1.0f), "floor"});
  scene.instances.push_back({1, glm::translate(glm::mat4(1.0f), {0, 0.2f, 0}), "card"});
  Material card;
  card.baseColor = grey;
  card.metallic = 0.0f;
  card.doubleSided = true;
  scene.materials.push_back(card);
  Material textured = card;
  textured.baseColor = glm::vec4(1.0f);
  textured.baseColorTexture = 0;
  scene.materials.push_back(textured);
  scene.sun.irradiance = 3.0f;
  scene.camera = Camera{{0.3f, 1.2f, 3.0f}, {0.0f, 0.5f, 0.0f}, {0, 1, 0}, 45.0f};
  return scene;
}

}  // namespace bounce::test
