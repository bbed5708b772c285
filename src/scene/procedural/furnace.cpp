// The white-furnace enclosure (see furnace.h): a room-sized box, inward facing, tessellated into
// half-metre quads so caches and probes see realistic triangle sizes.
#include "scene/procedural/furnace.h"

#include <string>

#include <fmt/format.h>

#include "scene/procedural/mesh_builder.h"

namespace bounce {

namespace {

const glm::vec3 kEnclosureMin{-2.0f, 0.0f, -2.5f};
const glm::vec3 kEnclosureMax{2.0f, 3.0f, 2.5f};
const glm::ivec3 kCells{8, 6, 10};  // 0.5 m cells

// Every vertex is a point of one integer lattice, computed by one expression, so the edges where
// two faces meet get bit-identical positions on both faces: that is what makes the box watertight.
glm::vec3 latticePoint(const glm::ivec3& index) {
  glm::vec3 p;
  for (int axis = 0; axis < 3; ++axis)
    p[axis] = kEnclosureMin[axis] + (kEnclosureMax[axis] - kEnclosureMin[axis]) *
                                        float(index[axis]) / float(kCells[axis]);
  return p;
}

// One face of the box, at the low (side 0) or high (side 1) end of `axis`, as an indexed grid
// facing into the box.
void addInwardFace(Geometry& g, int axis, int side) {
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  glm::vec3 inward{0.0f};
  inward[axis] = side == 0 ? 1.0f : -1.0f;
  const uint32_t first = uint32_t(g.positions.size());
  const uint32_t rowLength = uint32_t(kCells[b] + 1);
  for (int j = 0; j <= kCells[c]; ++j) {
    for (int i = 0; i <= kCells[b]; ++i) {
      glm::ivec3 index{0};
      index[axis] = side == 0 ? 0 : kCells[axis];
      index[b] = i;
      index[c] = j;
      glm::vec3 p = latticePoint(index);
      g.positions.push_back(p);
      g.normals.push_back(inward);
      g.uvs.push_back({p[b], p[c]});
    }
  }
  for (int j = 0; j < kCells[c]; ++j) {
    for (int i = 0; i < kCells[b]; ++i) {
      uint32_t v00 = first + uint32_t(j) * rowLength + uint32_t(i);
      uint32_t v10 = v00 + 1, v01 = v00 + rowLength, v11 = v01 + 1;
      // Walking b then c turns counter-clockwise around +axis (cross(e_b, e_c) = e_axis).
      if (side == 0)
        g.indices.insert(g.indices.end(), {v00, v10, v11, v00, v11, v01});
      else
        g.indices.insert(g.indices.end(), {v00, v11, v10, v00, v01, v11});
    }
  }
}

}  // namespace

Scene makeFurnaceScene(float albedo, glm::vec3 emission) {
  Scene scene;
  scene.name = "furnace";
  Material surface =
      procedural::lambertMaterial(fmt::format("furnace_albedo_{}", albedo), glm::vec3(albedo));
  surface.emissive = emission;
  const uint32_t material = procedural::addMaterial(scene, surface);

  Geometry enclosure;
  enclosure.material = material;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) addInwardFace(enclosure, axis, side);
  Mesh mesh;
  mesh.name = "furnace_enclosure";
  mesh.geometries.push_back(std::move(enclosure));
  procedural::addMeshInstance(scene, std::move(mesh));

  Camera camera;
  camera.position = {0.7f, 1.4f, 1.6f};
  camera.target = {-1.5f, 0.7f, -2.3f};
  camera.verticalFovDegrees = 70.0f;
  scene.camera = camera;
  // Nothing outside contributes: the box is closed, and the sun and sky stay off.
  scene.sun.irradiance = 0.0f;
  scene.sky.radiance = glm::vec3(0.0f);
  validateScene(scene, "furnace scene");
  return scene;
}

}  // namespace bounce
