// The sunroom's dimensions, shared by the scene builder and the tests that check its one opening.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce {

struct SunroomLayout {
  Aabb interior;        // the air inside the room: floor at y = min.y, ceiling at y = max.y
  float wallThickness;  // walls, floor and ceiling
  // The only opening: a window in the wall whose inner face is the plane z = interior.min.z,
  // spanning [windowMin, windowMax] in world (x, y).
  glm::vec2 windowMin;
  glm::vec2 windowMax;
};

const SunroomLayout& sunroomLayout();

}  // namespace bounce
