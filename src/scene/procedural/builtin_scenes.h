// The built-in procedural scenes, one file each; registry.cpp maps names to them. Each returns a
// complete scene (materials, meshes, instances, camera, sun, sky); the registry validates it.
#pragma once
#include "scene/scene.h"

namespace bounce::procedural {

Scene makeCornellScene();     // cornell.cpp: the Cornell box of ../shared/scenes/cornell_box
Scene makeSunroomScene();     // sunroom.cpp: a closed room lit through one window
Scene makeFoliageScene();     // foliage.cpp: trees and bushes with alpha-tested leaf cards
Scene makeManyLightsScene();  // manylights.cpp: a room with 64 coloured point lights
Scene makeCityScene();        // city.cpp: > 1M triangles of city blocks for BVH stress
// The furnace is declared in furnace.h, since tests vary its albedo and emission.

}  // namespace bounce::procedural
