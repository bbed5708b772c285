// The built-in procedural scenes, one file each; registry.cpp maps names to them. Each returns a
// complete scene (materials, meshes, instances, camera, sun, sky); the registry validates it.
#pragma once
#include <array>

#include "scene/scene.h"

namespace bounce::procedural {

Scene makeCornellScene();        // cornell.cpp: the Cornell box of ../shared/scenes/cornell_box
Scene makeSunroomScene();        // sunroom.cpp: a closed room lit through one window
Scene makeGlossySunroomScene();  // sunroom.cpp: the same with a glossy floor and a steel ball
Scene makeFoliageScene();        // foliage.cpp: trees and bushes with alpha-tested leaf cards
Scene makeManyLightsScene();     // manylights.cpp: a room with 64 coloured point lights
Scene makeCityScene();           // city.cpp: > 1M triangles of city blocks for BVH stress
Scene makeCity10kScene();        // city.cpp: the city on a larger grid, 10,000 street lights
Scene makeSpheresScene();  // spheres.cpp: rows of metal and dielectric spheres, rough to smooth
Scene makeSkinnedScene();  // skinned.cpp: a skinned tube and a morphing blob, animated
Scene makeSkinnedCrowdScene();  // skinned.cpp: 256 skinned tubes and 64 blobs (deformation cost)

// The spheres scene's grid: rows front to back are white metal, gold (the kSpheresMetalRows
// metal rows first), white dielectric, red dielectric; column c has roughness
// kSpheresRoughness[c]. Instance "sphere_<row>_<column>".
inline constexpr int kSpheresRows = 4;
inline constexpr int kSpheresMetalRows = 2;
inline constexpr int kSpheresColumns = 7;
inline constexpr std::array<float, kSpheresColumns> kSpheresRoughness = {0.02f, 0.1f,  0.2f, 0.35f,
                                                                         0.5f,  0.75f, 1.0f};
// The city's grids: 16 street lights to a block, each a light (an emissive cover and a spot
// light "street_light_<i>_beam"), so city has 1,024 and city-10k 10,000 spot lights.
inline constexpr int kCityBlocksPerSide = 8;
inline constexpr int kCity10kBlocksPerSide = 25;
inline constexpr int kCityStreetLightsPerBlock = 16;

// The furnace is declared in furnace.h, since tests vary its albedo and emission.

}  // namespace bounce::procedural
