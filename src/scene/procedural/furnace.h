// The white-furnace scene: a closed box whose every surface has Lambert albedo `albedo` and
// emits radiance `emission`. Light bounces inside forever, so the radiance leaving every point in
// every direction is the geometric series Le (1 + a + a^2 + ...) = Le / (1 - a): a renderer that
// shows anything else (structure, noise beyond its variance, a bias) loses or creates energy.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce {

// The enclosure is watertight (every edge shared by exactly two triangles), its normals face
// inwards, and the camera is inside. The built-in "furnace" uses albedo 0.5, emission 1.
Scene makeFurnaceScene(float albedo, glm::vec3 emission);

}  // namespace bounce
