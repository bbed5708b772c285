// The glTF loader: malformed files must give a bounce::Error naming the file and the problem
// (never a crash, hang or huge allocation), unusual valid files must load with the documented
// defaults, and the shared scenes must load with their known contents.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf_writer.h"
#include "harness.h"
#include "rt/cpu_trace.h"
#include "rt/scene_bvh.h"
#include "scene/default_light.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "scene/time_of_day.h"

namespace bounce {
namespace {

using nlohmann::json;
using test::GltfWriter;
using test::kFloat;
using test::kUnsignedInt;
using test::kUnsignedShort;
namespace fs = std::filesystem;

class GltfLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::tempDir(std::string("gltf-") +
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir); }

  // Loading `path` must throw bounce::Error whose message names the file and contains
  // `keyword`; and the `bounce` program given the file must exit with code 1 and the same
  // message on stderr (never crash, hang or render).
  static void expectError(const std::string& path, const std::string& keyword) {
    const std::string fileName = fs::path(path).filename().string();
    try {
      loadGltf(path);
      ADD_FAILURE() << path << " loaded, expected an error containing '" << keyword << "'";
    } catch (const Error& e) {
      std::string message = e.what();
      EXPECT_NE(message.find(fileName), std::string::npos)
          << "message does not name the file: " << message;
      EXPECT_NE(message.find(keyword), std::string::npos)
          << "message lacks '" << keyword << "': " << message;
    }
    test::CommandResult r = test::runCommand(
        test::bounceExe() + " render --res 8x8 --scene '" + path + "' --out '" + path + ".png'",
        60);
    EXPECT_EQ(r.exitCode, 1) << "bounce render --scene " << path << "\n" << r.output;
    EXPECT_NE(r.output.find("bounce: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(fileName), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(keyword), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path + ".png")) << "an image was written for a broken file";
  }

  // A 2x2 RGBA PNG next to the glTF.
  void writePng(const std::string& name) {
    const uint8_t pixels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0};
    ASSERT_NE(stbi_write_png((dir + "/" + name).c_str(), 2, 2, 4, pixels, 8), 0);
  }

  // A quad whose material's base colour texture is image `uri`.
  std::string texturedQuad(GltfWriter& w, const std::string& uri, json textureInfo = {}) {
    int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    int uv = w.addUvs({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
    textureInfo["index"] = 0;
    w.doc["images"] = json::array({{{"uri", uri}}});
    w.doc["textures"] = json::array({{{"source", 0}}});
    w.doc["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", textureInfo}}}}});
    w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}},
                                   {"indices", idx},
                                   {"material", 0}})}});
    return w.writeGltf(dir, "textured");
  }

  std::string dir;
};

// ---- malformed input ---------------------------------------------------------------------------

TEST_F(GltfLoaderTest, MissingFile) {
  expectError(dir + "/does_not_exist.gltf", "cannot open");
}

TEST_F(GltfLoaderTest, EmptyFile) {
  expectError(GltfWriter::writeText(dir + "/empty.gltf", ""), "empty");
}

TEST_F(GltfLoaderTest, TruncatedGlb) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGlb(dir, "cut");
  fs::resize_file(path, fs::file_size(path) / 2);
  expectError(path, "truncated");
}

TEST_F(GltfLoaderTest, TruncatedJson) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGltf(dir, "cut");
  fs::resize_file(path, fs::file_size(path) / 2);
  expectError(path, "invalid JSON");
}

TEST_F(GltfLoaderTest, InvalidJson) {
  expectError(GltfWriter::writeText(dir + "/garbage.gltf", "{ \"asset\": [1, 2,, }"),
              "invalid JSON");
}

TEST_F(GltfLoaderTest, BadGlbMagic) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGlb(dir, "magic");
  std::fstream(path, std::ios::in | std::ios::out | std::ios::binary).write("gLtX", 4);
  expectError(path, "bad magic");
}

TEST_F(GltfLoaderTest, GlbLengthBeyondFile) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGlb(dir, "length");
  uint32_t length = 1u << 30;
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(8);
  f.write(reinterpret_cast<const char*>(&length), 4);
  f.close();
  expectError(path, "truncated");
}

TEST_F(GltfLoaderTest, AccessorOutOfBufferView) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0]["count"] = 40;  // the view holds 4 positions
  expectError(w.writeGltf(dir, "accessor"), "exceed bufferView");
}

TEST_F(GltfLoaderTest, AccessorOffsetOutOfBufferView) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0]["byteOffset"] = 1000000;
  expectError(w.writeGltf(dir, "offset"), "exceed bufferView");
}

TEST_F(GltfLoaderTest, BufferViewOutOfBuffer) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["bufferViews"][0]["byteLength"] = 100000;
  expectError(w.writeGltf(dir, "view"), "lies outside buffer 0");
}

TEST_F(GltfLoaderTest, BufferViewRefersToMissingBuffer) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["bufferViews"][0]["buffer"] = 3;
  expectError(w.writeGltf(dir, "buffer"), "refers to buffer 3");
}

TEST_F(GltfLoaderTest, AccessorRefersToMissingBufferView) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0]["bufferView"] = 9;
  expectError(w.writeGltf(dir, "noview"), "refers to bufferView 9");
}

TEST_F(GltfLoaderTest, MissingBufferFile) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGltf(dir, "nobin");
  fs::remove(dir + "/nobin.bin");
  expectError(path, "nobin.bin");
  expectError(path, "not found");
}

TEST_F(GltfLoaderTest, MissingTextureFile) {
  GltfWriter w;
  expectError(texturedQuad(w, "missing_albedo.png"), "missing_albedo.png");
}

TEST_F(GltfLoaderTest, UndecodableTextureFile) {
  GltfWriter w;
  GltfWriter::writeText(dir + "/broken.png", "this is not a PNG at all");
  std::string path = texturedQuad(w, "broken.png");
  expectError(path, "broken.png");
  expectError(path, "cannot decode");
}

TEST_F(GltfLoaderTest, NaNPosition) {
  GltfWriter w;
  float nan = std::nanf("");
  int pos = w.addPositions({{0, 0, 0}, {1, nan, 0}, {1, 1, 0}});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  expectError(w.writeGltf(dir, "nan"), "NaN");
}

TEST_F(GltfLoaderTest, InfinitePosition) {
  GltfWriter w;
  float inf = INFINITY;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, inf, 0}});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  expectError(w.writeGltf(dir, "inf"), "infinite");
}

TEST_F(GltfLoaderTest, UnsupportedRequiredExtension) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  w.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  expectError(w.writeGltf(dir, "draco"),
              "requires unsupported extension KHR_draco_mesh_compression");
}

TEST_F(GltfLoaderTest, AbsurdAccessorCount) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0]["count"] = 1ull << 40;
  expectError(w.writeGltf(dir, "absurd"), "exceeds the limit of 2^28");
}

TEST_F(GltfLoaderTest, AbsurdCountWithoutBufferView) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0].erase("bufferView");
  w.doc["accessors"][0]["count"] = 200000000;  // under 2^28, but backed by nothing
  expectError(w.writeGltf(dir, "unbacked"), "without a bufferView");
}

TEST_F(GltfLoaderTest, IndexOutOfVertexRange) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 9});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  expectError(w.writeGltf(dir, "index"), "index 9 out of range");
}

TEST_F(GltfLoaderTest, IndexCountNotMultipleOfThree) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int idx = w.addIndices16({0, 1, 2, 0});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  expectError(w.writeGltf(dir, "count"), "not a multiple of 3");
}

TEST_F(GltfLoaderTest, NodeRefersToMissingMesh) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["nodes"][0]["mesh"] = 5;
  expectError(w.writeGltf(dir, "mesh"), "refers to mesh 5");
}

TEST_F(GltfLoaderTest, SceneRefersToMissingNode) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["scenes"] = json::array({{{"nodes", {0, 7}}}});
  expectError(w.writeGltf(dir, "node"), "refers to node 7");
}

TEST_F(GltfLoaderTest, NodeCycle) {
  GltfWriter w;
  w.addQuadScene();
  w.addNode({{"children", {2}}}, false);  // node 1 -> 2 -> 1, reached from node 0
  w.addNode({{"children", {1}}}, false);
  w.doc["nodes"][0]["children"] = {1};
  expectError(w.writeGltf(dir, "cycle"), "cycle");
}

TEST_F(GltfLoaderTest, PositionWithWrongType) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["accessors"][0]["type"] = "VEC2";
  expectError(w.writeGltf(dir, "type"), "has type VEC2, expected VEC3");
}

TEST_F(GltfLoaderTest, PrimitiveWithoutPosition) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
  expectError(w.writeGltf(dir, "noposition"), "no POSITION");
}

TEST_F(GltfLoaderTest, PrimitiveRefersToMissingMaterial) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["meshes"][0]["primitives"][0]["material"] = 7;
  expectError(w.writeGltf(dir, "material"), "refers to material 7");
}

TEST_F(GltfLoaderTest, MaterialRefersToMissingTexture) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["materials"] =
      json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 3}}}}}}});
  w.doc["meshes"][0]["primitives"][0]["material"] = 0;
  expectError(w.writeGltf(dir, "texture"), "refers to texture 3");
}

TEST_F(GltfLoaderTest, NonFiniteNodeTransform) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["nodes"][0]["scale"] = {1e39, 1.0, 1.0};  // finite as JSON, infinite as float
  expectError(w.writeGltf(dir, "transform"), "non-finite transform");
}

TEST_F(GltfLoaderTest, BadSparseIndex) {
  GltfWriter w;
  w.addQuadScene();
  uint16_t sparseIndex = 50;
  glm::vec3 value(5.0f);
  int indexView = w.addView(&sparseIndex, 2);
  int valueView = w.addView(&value, 12);
  w.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", indexView}, {"componentType", kUnsignedShort}}},
      {"values", {{"bufferView", valueView}}}};
  expectError(w.writeGltf(dir, "sparse"), "sparse index 50 out of range");
}

TEST_F(GltfLoaderTest, UnsupportedVersion) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["asset"]["version"] = "1.0";
  expectError(w.writeGltf(dir, "version"), "version '1.0' is not supported");
}

// tinygltf converts extras recursively; absurd nesting must be refused before it overflows the
// stack.
TEST_F(GltfLoaderTest, DeeplyNestedJson) {
  std::string text = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(100000, '[') +
                     std::string(100000, ']') + "}";
  expectError(GltfWriter::writeText(dir + "/deep.gltf", text), "nested deeper than");
}

// A PNG header claiming 16000 x 8000 pixels (512 MB as RGBA8) must be refused before decoding
// allocates.
TEST_F(GltfLoaderTest, ImageWithAbsurdSize) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,
                              0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (uint32_t side : {16000u, 8000u})
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(uint8_t(side >> shift));
  png.insert(png.end(), {8, 6, 0, 0, 0, 0, 0, 0, 0});  // 8-bit RGBA, CRC (unchecked)
  GltfWriter::writeBytes(dir + "/huge.png", png);
  GltfWriter w;
  expectError(texturedQuad(w, "huge.png"), "16000x8000 is outside");
}

// ---- valid but unusual -------------------------------------------------------------------------

// One triangle with nothing but positions: no indices, normals, UVs or materials.
TEST_F(GltfLoaderTest, BareTriangleGetsDefaults) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {2, 0, 1}, {0, 1, 1}});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  Scene scene = loadGltf(w.writeGltf(dir, "bare"));

  EXPECT_EQ(scene.name, "bare");
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].baseColor, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
  EXPECT_EQ(scene.materials[0].roughness, 1.0f);
  EXPECT_EQ(scene.materials[0].metallic, 0.0f);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 1u);
  const Geometry& g = scene.meshes[0].geometries.at(0);
  EXPECT_EQ(g.material, 0u);
  EXPECT_EQ(g.indices, (std::vector<uint32_t>{0, 1, 2}));
  ASSERT_EQ(g.normals.size(), 3u);
  ASSERT_EQ(g.uvs.size(), 3u);
  EXPECT_TRUE(g.tangents.empty());
  glm::vec3 e1 = g.positions[1] - g.positions[0], e2 = g.positions[2] - g.positions[0];
  glm::vec3 faceNormal = glm::normalize(glm::cross(e1, e2));
  for (int v = 0; v < 3; ++v) {
    EXPECT_NEAR(glm::length(g.normals[v]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(g.normals[v], glm::normalize(e1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(g.normals[v], glm::normalize(e2)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(g.normals[v], faceNormal), 1.0f, 1e-6f);  // counter-clockwise = front
    EXPECT_EQ(g.uvs[v], glm::vec2(0.0f));
  }
  EXPECT_FALSE(scene.camera.has_value());
  EXPECT_EQ(scene.sun.irradiance, 0.0f);
  EXPECT_EQ(scene.sky.radiance, glm::vec3(0.0f));
}

TEST_F(GltfLoaderTest, GlbAndDataUriLoadLikeExternalBuffers) {
  GltfWriter w;
  w.addQuadScene();
  Scene external = loadGltf(w.writeGltf(dir, "external"));
  Scene glb = loadGltf(w.writeGlb(dir, "binary"));
  GltfWriter w2;
  w2.addQuadScene();
  Scene embedded = loadGltf(w2.writeGltfDataUri(dir, "embedded"));
  for (const Scene* s : {&glb, &embedded}) {
    ASSERT_EQ(s->meshes.size(), 1u);
    EXPECT_EQ(s->meshes[0].geometries[0].positions, external.meshes[0].geometries[0].positions);
    EXPECT_EQ(s->meshes[0].geometries[0].indices, external.meshes[0].geometries[0].indices);
  }
  EXPECT_EQ(external.triangleCount(), 2u);
}

// Interleaved attributes (byteStride), 32-bit indices, a triangle strip and a points primitive
// (skipped) in one mesh.
TEST_F(GltfLoaderTest, StridedStripAndSkippedPoints) {
  GltfWriter w;
  struct Vertex {
    glm::vec3 position;
    glm::vec2 uv;
  };
  std::vector<Vertex> vertices = {
      {{0, 0, 0}, {0, 0}}, {{1, 0, 0}, {1, 0}}, {{0, 1, 0}, {0, 1}}, {{1, 1, 0}, {1, 1}}};
  int view = w.addView(vertices.data(), vertices.size() * sizeof(Vertex), sizeof(Vertex));
  int pos = w.addAccessor(view, kFloat, 4, "VEC3");
  int uv = w.addAccessor(view, kFloat, 4, "VEC2");
  w.doc["accessors"][uv]["byteOffset"] = 12;
  std::vector<uint32_t> strip = {0, 1, 2, 3};
  int idx = w.addAccessor(w.addView(strip.data(), 16), kUnsignedInt, 4, "SCALAR");
  json triangles = {
      {"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}, {"mode", 5}};
  json points = {{"attributes", {{"POSITION", pos}}}, {"mode", 0}};
  w.doc["meshes"].push_back({{"primitives", {points, triangles}}});
  w.addNode({{"mesh", 0}});
  Scene scene = loadGltf(w.writeGltf(dir, "strip"));

  ASSERT_EQ(scene.meshes[0].geometries.size(), 1u);
  const Geometry& g = scene.meshes[0].geometries[0];
  EXPECT_EQ(g.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));  // odd triangle flipped
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(g.uvs[v], vertices[v].uv);
    EXPECT_NEAR(g.normals[v].z, 1.0f, 1e-6f);  // both triangles face +Z
  }
}

// Normalized 16-bit UVs, 8-bit indices; a file without "scenes" renders its root nodes; a
// primitive without a material gets the default one beside the file's materials.
TEST_F(GltfLoaderTest, QuantizedUvsByteIndicesNoScenesMixedMaterials) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  std::vector<uint16_t> uvs = {0, 0, 65535, 0, 65535, 32768, 0, 65535};
  int uv = w.addAccessor(w.addView(uvs.data(), 16), kUnsignedShort, 4, "VEC2");
  w.doc["accessors"][uv]["normalized"] = true;
  std::vector<uint8_t> indices = {0, 1, 2, 0, 2, 3};
  int idx = w.addAccessor(w.addView(indices.data(), 6), 5121, 6, "SCALAR");
  json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv}};
  json red = {{"attributes", attributes}, {"indices", idx}, {"material", 0}};
  json plain = {{"attributes", attributes}, {"indices", idx}};
  w.doc["meshes"].push_back({{"primitives", {red, plain}}});
  w.doc["materials"] = {
      {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}}};
  w.doc.erase("scene");
  w.doc.erase("scenes");
  w.addNode({{"mesh", 0}, {"children", {1}}}, false);
  w.addNode({{"mesh", 0}, {"translation", {0, 0, 1}}}, false);
  std::string path = w.writeGltf(dir, "quantized");
  // writeGltf adds an empty scene list entry when none exists; remove it again.
  json doc = json::parse(std::ifstream(path));
  doc.erase("scenes");
  GltfWriter::writeText(path, doc.dump());
  Scene scene = loadGltf(path);

  EXPECT_EQ(scene.instances.size(), 2u);  // node 0 is the only root; node 1 is its child
  EXPECT_EQ(scene.instances[1].transform[3], glm::vec4(0, 0, 1, 1));
  ASSERT_EQ(scene.meshes[0].geometries.size(), 2u);
  const Geometry& g = scene.meshes[0].geometries[0];
  EXPECT_EQ(g.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(g.uvs[1], glm::vec2(1.0f, 0.0f));
  EXPECT_NEAR(g.uvs[2].y, 32768.0f / 65535.0f, 1e-7f);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[g.material].name, "red");
  const Material& fallback = scene.materials[scene.meshes[0].geometries[1].material];
  EXPECT_EQ(fallback.baseColor, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
}

TEST_F(GltfLoaderTest, DropsSomeZeroAreaTriangles) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 1, 3, 2, 2, 1});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  Scene scene = loadGltf(w.writeGltf(dir, "partial"));
  EXPECT_EQ(scene.meshes[0].geometries[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

// A valid file whose only triangles are degenerate loads as an empty scene, which renders as
// sky (test_gltf_render.cpp); it says which primitive and mesh it skipped.
TEST_F(GltfLoaderTest, AllTrianglesZeroArea) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 3, 1});  // collinear, then a repeated vertex
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "flat"), warnings);
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(scene.instances.empty());
  EXPECT_EQ(scene.triangleCount(), 0u);
  EXPECT_FALSE(scene.materials.empty());
  EXPECT_EQ(warnings.summary(), (std::vector<std::string>{
                                    "mesh 0 primitive 0: skipped: all 2 triangles have zero area",
                                    "mesh 0: no triangles to render, nodes using it are skipped"}));
  rt::SceneBvh bvh = rt::buildSceneBvh(scene);  // an empty TLAS, not an error
  EXPECT_TRUE(bvh.instances.empty());
}

// One primitive without a valid triangle beside a valid one: only that primitive is skipped.
TEST_F(GltfLoaderTest, PrimitiveWithoutValidTrianglesAmongValidOnes) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int quad = w.addIndices16({0, 1, 2, 0, 2, 3});
  int flat = w.addIndices16({0, 0, 1, 2, 2, 2});
  json valid = {{"attributes", {{"POSITION", pos}}}, {"indices", quad}};
  json degenerate = {{"attributes", {{"POSITION", pos}}}, {"indices", flat}};
  w.doc["meshes"].push_back({{"name", "mixed"}, {"primitives", {degenerate, valid, degenerate}}});
  w.addNode({{"mesh", 0}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "mixed"), warnings);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.meshes[0].geometries.size(), 1u);
  EXPECT_EQ(scene.meshes[0].geometries[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(warnings.summary(),
            (std::vector<std::string>{"skipped: every triangle has zero area: 2 primitives (4 "
                                      "triangles), e.g. mesh 0 ('mixed') primitive 0"}));
}

// glTF animations hide objects with scale 0. A node that stays singular is skipped with a
// warning; so are the children of a node that flattens space.
TEST_F(GltfLoaderTest, ZeroScaleNodeIsSkipped) {
  GltfWriter w;
  w.addQuadScene();  // node 0
  w.addNode({{"mesh", 0}, {"name", "hidden"}, {"scale", {0.0, 0.0, 0.0}}});
  w.addNode({{"mesh", 0}, {"scale", {1.0, 0.0, 1.0}}, {"children", {3}}});
  w.addNode({{"mesh", 0}, {"translation", {0.0, 0.0, 1.0}}}, false);
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "zero_scale"), warnings);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].name, "node 0");
  EXPECT_EQ(warnings.summary(),
            (std::vector<std::string>{"skipped: singular transform (scale 0), nothing to show: 3 "
                                      "nodes, e.g. node 1 ('hidden')"}));
  EXPECT_EQ(rt::buildSceneBvh(scene).instances.size(), 1u);
}

// A node animated from scale 0 up is kept: hidden (out of the TLAS) while singular, traced once
// its animated transform is invertible, with no error on the way.
TEST_F(GltfLoaderTest, AnimatedZeroScaleNodeIsHiddenUntilScaledUp) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["nodes"][0]["scale"] = {0.0, 0.0, 0.0};
  const float times[] = {0.0f, 1.0f};
  const float scales[] = {0, 0, 0, 1, 1, 1};
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(scales, sizeof(scales)), kFloat, 2, "VEC3");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "scale"}}}}}}}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "grows"), warnings);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(warnings.count("starts with a singular transform (scale 0): hidden until its "
                           "animation scales it up"),
            1u);

  rt::SceneBvh bvh = rt::buildSceneBvh(scene);
  EXPECT_NE(bvh.instances[0].flags & gpu::GPU_INSTANCE_HIDDEN, 0u);
  EXPECT_EQ(bvh.tlasNodes[0].leftCount, 0u) << "a hidden instance must not be in the TLAS";
  rt::BruteForceTracer hidden(scene);
  rt::Ray ray{{0.5f, 0.5f, 1.0f}, {0.0f, 0.0f, -1.0f}, 0.0f};
  EXPECT_FALSE(hidden.closestHit(ray, 10.0f).hit);

  std::vector<glm::mat4> transforms = {scene.instances[0].transform};
  evaluateTransforms(scene.animation, 0.999f, {}, transforms);
  rt::setInstanceTransform(bvh.instances[0], transforms[0]);
  EXPECT_EQ(bvh.instances[0].flags & gpu::GPU_INSTANCE_HIDDEN, 0u);
  bvh.tlasNodes = rt::buildTlas(bvh.instances, bvh.meshBounds);
  EXPECT_EQ(bvh.tlasNodes[0].leftCount, 1u);
  EXPECT_EQ(bvh.tlasNodes[0].leftIndex, 0u);
  scene.instances[0].transform = transforms[0];
  rt::BruteForceTracer shown(scene);
  EXPECT_TRUE(shown.closestHit(ray, 10.0f).hit);
}

TEST_F(GltfLoaderTest, SparseAccessorOverridesBase) {
  GltfWriter w;
  w.addQuadScene();
  uint16_t sparseIndex = 2;
  glm::vec3 value(1.0f, 2.0f, 0.0f);
  int indexView = w.addView(&sparseIndex, 2);
  int valueView = w.addView(&value, 12);
  w.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", indexView}, {"componentType", kUnsignedShort}}},
      {"values", {{"bufferView", valueView}}}};
  Scene scene = loadGltf(w.writeGltf(dir, "sparse"));
  EXPECT_EQ(scene.meshes[0].geometries[0].positions[2], value);
  EXPECT_EQ(scene.meshes[0].geometries[0].positions[1], glm::vec3(1, 0, 0));
}

// Transforms compose parent * child, TRS and matrix forms agree, and two nodes sharing a mesh
// give two instances of one Mesh.
TEST_F(GltfLoaderTest, HierarchyAndInstancing) {
  GltfWriter w;
  w.addQuadScene();  // node 0: the quad
  w.doc["nodes"][0]["translation"] = {10.0, 0.0, 0.0};
  w.doc["nodes"][0]["children"] = {1};
  // Child: 90 degrees about +Z, uniform scale 2, as a matrix (column-major).
  w.addNode({{"mesh", 0}, {"matrix", {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 0, 0, 5, 1}}}, false);
  Scene scene = loadGltf(w.writeGltf(dir, "tree"));

  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.instances[0].mesh, scene.instances[1].mesh);
  glm::vec3 corner = glm::vec3(scene.instances[1].transform * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(glm::distance(corner, glm::vec3(10, 2, 5)), 0.0f, 1e-5f);
  EXPECT_EQ(scene.triangleCount(), 4u);
  EXPECT_EQ(scene.uniqueTriangleCount(), 2u);
}

TEST_F(GltfLoaderTest, PunctualLightsAndCamera) {
  GltfWriter w;
  w.addQuadScene();
  w.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 20.0}},
      {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}}};
  double s = std::sqrt(0.5);
  w.addNode({{"translation", {1.0, 2.0, 3.0}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.addNode({{"translation", {0.0, 4.0, 0.0}},
             {"rotation", {-s, 0.0, 0.0, s}},  // -90 degrees about X: -Z turns to -Y
             {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  w.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
  w.addNode({{"camera", 0}, {"translation", {0.0, 0.0, 7.0}}});
  Scene scene = loadGltf(w.writeGltf(dir, "lights"));

  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, PunctualLight::Type::Point);
  EXPECT_EQ(scene.lights[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(scene.lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(scene.lights[0].intensity, 20.0f);
  EXPECT_EQ(scene.lights[1].type, PunctualLight::Type::Spot);
  EXPECT_NEAR(glm::distance(scene.lights[1].direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(scene.lights[1].outerConeAngle, 0.5f, 1e-7f);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->position, glm::vec3(0, 0, 7));
  EXPECT_NEAR(glm::distance(scene.camera->target, glm::vec3(0, 0, 6)), 0.0f, 1e-6f);
  EXPECT_NEAR(scene.camera->verticalFovDegrees, glm::degrees(0.5f), 1e-4f);
}

// Textures decode to RGBA8, and the base colour KHR_texture_transform is baked into the UVs.
TEST_F(GltfLoaderTest, TextureDecodedAndTransformBaked) {
  writePng("tile.png");
  GltfWriter w;
  json info = {
      {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}, {"scale", {2.0, 3.0}}}}}}};
  Scene scene = loadGltf(texturedQuad(w, "tile.png", info));

  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].width, 2);
  EXPECT_EQ(scene.images[0].height, 2);
  ASSERT_EQ(scene.images[0].rgba.size(), 16u);
  EXPECT_EQ(scene.images[0].rgba[4 * 3 + 3], 0);  // alpha of the last texel survives
  EXPECT_EQ(scene.materials.at(0).baseColorTexture, 0);
  const Geometry& g = scene.meshes[0].geometries[0];
  EXPECT_NEAR(glm::distance(g.uvs[2], glm::vec2(2.5f, 3.0f)), 0.0f, 1e-6f);  // (1,1) -> S then T
}

// COLOR_0 in each encoding glTF 2.0 allows (§3.7.2.1), read as linear RGBA in [0, 1]; a
// primitive without it keeps an empty stream (white).
TEST_F(GltfLoaderTest, VertexColorsInEveryEncoding) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  const uint8_t bytes[16] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 51, 102, 153, 255};
  int u8 = w.addAccessor(w.addView(bytes, sizeof(bytes)), 5121, 4, "VEC4");
  w.doc["accessors"][u8]["normalized"] = true;
  const uint16_t shorts[16] = {65535, 0, 0, 65535, 0, 32768, 0, 65535, 0, 0, 0, 0, 1, 2, 3, 4};
  int u16 = w.addAccessor(w.addView(shorts, sizeof(shorts)), kUnsignedShort, 4, "VEC4");
  w.doc["accessors"][u16]["normalized"] = true;
  const float floats[12] = {0.25f, 0.5f, 0.75f, 1, 1, 1, 2.0f, -1.0f, 0, 0, 0, 0};
  int f32 = w.addAccessor(w.addView(floats, sizeof(floats)), kFloat, 4, "VEC3");
  auto primitive = [&](int colors) {
    json attributes = {{"POSITION", pos}};
    if (colors >= 0) attributes["COLOR_0"] = colors;
    return json{{"attributes", attributes}, {"indices", idx}};
  };
  w.doc["meshes"].push_back(
      {{"primitives", {primitive(u8), primitive(u16), primitive(f32), primitive(-1)}}});
  w.addNode({{"mesh", 0}});
  Scene scene = loadGltf(w.writeGltf(dir, "colors"));
  const std::vector<Geometry>& g = scene.meshes.at(0).geometries;
  ASSERT_EQ(g.size(), 4u);
  ASSERT_EQ(g[0].colors.size(), 4u);
  EXPECT_EQ(g[0].colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(g[0].colors[1], glm::vec4(0, 1, 0, 128.0f / 255.0f));
  EXPECT_EQ(g[0].colors[3], glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
  ASSERT_EQ(g[1].colors.size(), 4u);
  EXPECT_EQ(g[1].colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(g[1].colors[1].y, 32768.0f / 65535.0f);
  ASSERT_EQ(g[2].colors.size(), 4u);
  EXPECT_EQ(g[2].colors[0], glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));  // VEC3: alpha 1
  EXPECT_EQ(g[2].colors[2], glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));    // clamped to [0, 1]
  EXPECT_TRUE(g[3].colors.empty());
}

TEST_F(GltfLoaderTest, VertexColorsOfAnInvalidType) {
  GltfWriter w;
  w.addQuadScene();
  const uint8_t bytes[12] = {};
  int u8 = w.addAccessor(w.addView(bytes, sizeof(bytes)), 5121, 4, "VEC3");  // not normalized
  w.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = u8;
  expectError(w.writeGltf(dir, "raw_bytes"), "COLOR_0 has componentType 5121");
}

// Every feature Bounce does not draw is named in exactly one line per file, however often it
// is used, with the count of its uses; what Bounce supports is not named.
TEST_F(GltfLoaderTest, IgnoredFeaturesAreNamedOnce) {
  writePng("tile.png");
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int uv = w.addUvs({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  w.doc["images"] = json::array({{{"uri", "tile.png"}}});
  w.doc["samplers"] = json::array({{{"wrapS", 33071}, {"wrapT", 33071}}});  // CLAMP_TO_EDGE
  w.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  w.doc["extensionsUsed"] = {"KHR_materials_sheen",        "KHR_materials_clearcoat",
                             "KHR_materials_transmission", "EXT_mesh_gpu_instancing",
                             "KHR_texture_transform",      "KHR_materials_emissive_strength"};
  const int kUses = 3;
  for (int i = 0; i < kUses; ++i) {
    json transform = {{"KHR_texture_transform", {{"scale", {2.0, 2.0}}}}};
    w.doc["materials"].push_back(
        {{"name", "m" + std::to_string(i)},
         {"alphaMode", "BLEND"},
         {"occlusionTexture", {{"index", 0}}},
         {"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}, {"extensions", transform}}}}},
         {"extensions",
          {{"KHR_materials_sheen", json::object()},
           {"KHR_materials_clearcoat", json::object()},
           {"KHR_materials_emissive_strength", {{"emissiveStrength", 2.0}}}}}});
    json primitive = {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}, {"TEXCOORD_1", uv}}},
                      {"indices", idx},
                      {"material", i}};
    w.doc["meshes"].push_back({{"primitives", {primitive}}});
    w.addNode({{"mesh", i}});
  }
  // Skins and morph targets are supported (test_gltf_skin.cpp); an animated node that places
  // no mesh and is no joint is not.
  int joint = w.addNode({{"name", "empty"}});
  const float times[] = {0.0f, 1.0f};
  const float moves[] = {0, 0, 0, 1, 0, 0};
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(moves, sizeof(moves)), kFloat, 2, "VEC3");
  json channel = {{"sampler", 0}, {"target", {{"node", joint}, {"path", "translation"}}}};
  w.doc["animations"] = json::array({{{"samplers", {{{"input", in}, {"output", out}}}},
                                      {"channels", json::array({channel, channel, channel})}}});
  w.doc["cameras"] = {
      {{"type", "orthographic"},
       {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 9.0}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
  for (int camera : {0, 1, 1}) w.addNode({{"camera", camera}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "features"), warnings);
  EXPECT_EQ(scene.instances.size(), size_t(kUses));

  const std::vector<std::string> lines = warnings.summary();
  auto linesNaming = [&](const std::string& feature) {
    return std::count_if(lines.begin(), lines.end(), [&](const std::string& line) {
      return line.find(feature) != std::string::npos;
    });
  };
  auto lineNaming = [&](const std::string& feature) {
    auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& line) {
      return line.find(feature) != std::string::npos;
    });
    return it == lines.end() ? std::string() : *it;
  };
  std::string all;
  for (const std::string& line : lines) all += line + "\n";
  SCOPED_TRACE(all);
  for (const char* feature : {"occlusionTexture is ignored", "KHR_materials_sheen is ignored",
                              "KHR_materials_clearcoat is ignored", "alphaMode BLEND",
                              "TEXCOORD_1 and higher", "nodes that place no mesh"}) {
    EXPECT_EQ(linesNaming(feature), 1) << feature;
    EXPECT_NE(lineNaming(feature).find(": " + std::to_string(kUses) + " "), std::string::npos)
        << feature << ": expected the count of its " << kUses << " uses";
  }
  // One texture, used by every material: its sampler is named once, as one use.
  EXPECT_EQ(linesNaming("sampler wrap and filter modes are ignored"), 1);
  // Named from extensionsUsed alone (no used material or loaded object carries them).
  EXPECT_EQ(linesNaming("KHR_materials_transmission is ignored: surfaces are opaque"), 1);
  EXPECT_EQ(linesNaming("EXT_mesh_gpu_instancing is ignored"), 1);
  EXPECT_EQ(linesNaming("cameras other than perspective ones are ignored"), 1);
  EXPECT_EQ(linesNaming("cameras after the first perspective one are ignored"), 1);
  EXPECT_EQ(linesNaming("KHR_texture_transform"), 0) << "supported: baked into the UVs";
  EXPECT_EQ(linesNaming("emissive_strength"), 0) << "supported";
  EXPECT_EQ(lines.size(), 11u);
}

// 20 meshes that each drop one zero-area triangle give one line with the count, the total and
// the first example, not 20 lines; the one-argument loader prints exactly that line.
TEST_F(GltfLoaderTest, RepeatedWarningsAreSummarised) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3, 0, 0, 1});
  const int kMeshes = 20;
  for (int i = 0; i < kMeshes; ++i) {
    w.doc["meshes"].push_back(
        {{"name", "m" + std::to_string(i)},
         {"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}});
    w.addNode({{"mesh", i}});
  }
  std::string path = w.writeGltf(dir, "many");
  LoadWarnings warnings;
  Scene scene = loadGltf(path, warnings);
  EXPECT_EQ(scene.triangleCount(), uint64_t(2 * kMeshes));
  const std::string line =
      "dropped zero-area triangles: 20 primitives (20 triangles), e.g. mesh 0 ('m0') primitive 0";
  EXPECT_EQ(warnings.summary(), std::vector<std::string>{line});

  testing::internal::CaptureStderr();
  loadGltf(path);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "warning: " + path + ": " + line + "\n");
}

// An unlit file (no sun, sky, punctual light or emitter above radiance 1) gets the default daylight
// unless
// --sun or --sky is given; a file with any light of its own keeps it.
TEST_F(GltfLoaderTest, DefaultLightForAnUnlitFile) {
  GltfWriter w;
  w.addQuadScene();
  std::string path = w.writeGltf(dir, "unlit");
  Scene scene = loadGltf(path);
  EXPECT_FALSE(hasAnyLight(scene));
  Scene lit = scene;
  std::optional<std::string> note = applyDefaultLight(lit, {}, path);
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find(path + " has no lights: using a daylight sky and sun"), std::string::npos)
      << *note;
  EXPECT_TRUE(hasAnyLight(lit));
  EXPECT_EQ(lit.sun.irradiance, kDaylightSunKilolux);
  EXPECT_EQ(lit.sky.model, SkyModel::Daylight);
  // The built-in daylight at mid-morning: well above the horizon, not straight down.
  EXPECT_EQ(lit.sun.direction, -towardSunAt(kDefaultSunHours));
  EXPECT_GT(-lit.sun.direction.y, std::sin(glm::radians(30.0f)));
  EXPECT_LT(-lit.sun.direction.y, std::sin(glm::radians(60.0f)));

  for (bool sky : {false, true}) {
    Scene dark = scene;
    SceneOverrides overrides;
    if (sky)
      overrides.sky = parseSky("0,0,0");
    else
      overrides.sun = parseSun("0,-1,0:0");
    applyOverrides(dark, overrides);
    EXPECT_FALSE(applyDefaultLight(dark, overrides, path).has_value());
    EXPECT_FALSE(hasAnyLight(dark)) << "an explicit --sun or --sky keeps the scene as given";
  }
  // Emission within glTF's core range (emissiveFactor <= 1) is a glowing detail, not a lamp:
  // the scene still gets the daylight. A lamp raised by KHR_materials_emissive_strength keeps
  // the scene as given.
  Scene glowing = scene;
  glowing.materials[0].emissive = glm::vec3(0.0f, 0.0f, 1.0f);
  EXPECT_TRUE(applyDefaultLight(glowing, {}, path).has_value());
  Scene lamp = scene;
  lamp.materials[0].emissive = glm::vec3(17.0f, 12.0f, 4.0f);
  EXPECT_FALSE(applyDefaultLight(lamp, {}, path).has_value());
  EXPECT_EQ(lamp.sun.irradiance, 0.0f);
  Scene bulb = scene;
  bulb.lights.push_back(PunctualLight{});
  EXPECT_FALSE(applyDefaultLight(bulb, {}, path).has_value());
}

// The default light is for glTF files only; built-in scenes are lit as designed, so each must
// have a light of its own (the furnace: walls emitting radiance 1, which counts for a built-in
// scene although it would not make a glTF file "lit").
TEST(DefaultLight, EveryBuiltinSceneHasItsOwnLight) {
  for (const std::string& name : builtinSceneNames()) {
    // 1.9 M (city-10k: 18.7 M) triangles to build; lit by their sun, sky and street lights.
    if (name == "city" || name == "city-10k") continue;
    const Scene scene = *makeBuiltinScene(name);
    const bool emits = std::any_of(scene.materials.begin(), scene.materials.end(),
                                   [](const Material& m) { return m.emissive != glm::vec3(0.0f); });
    EXPECT_TRUE(hasAnyLight(scene) || emits) << name;
  }
}

// ---- the shared scenes -------------------------------------------------------------------------

// Each shared scene is loaded once per test binary; the load time is printed for the record.
const Scene& sharedScene(const std::string& relativePath) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(relativePath);
  if (it != cache.end()) return it->second;
  auto start = std::chrono::steady_clock::now();
  Scene scene = loadGltf(test::sharedDir() + "/scenes/" + relativePath);
  double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ loaded   ] %s in %.0f ms\n", relativePath.c_str(), ms);
  return cache.emplace(relativePath, std::move(scene)).first->second;
}

const Material& materialNamed(const Scene& scene, const std::string& name) {
  for (const Material& m : scene.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

TEST(SharedScenes, CornellBox) {
  const Scene& scene = sharedScene("cornell_box/cornell_box.gltf");
  EXPECT_EQ(scene.name, "cornell_box");
  EXPECT_EQ(scene.meshes.size(), 8u);
  EXPECT_EQ(scene.instances.size(), 8u);
  EXPECT_EQ(scene.triangleCount(), 32u);
  const Material& white = materialNamed(scene, "cb_white");
  EXPECT_NEAR(white.baseColor.x, 0.725f, 1e-6f);
  EXPECT_NEAR(white.baseColor.y, 0.71f, 1e-6f);
  EXPECT_NEAR(white.baseColor.z, 0.68f, 1e-6f);
  EXPECT_EQ(white.metallic, 0.0f);
  EXPECT_EQ(white.roughness, 1.0f);
  const Material& light = materialNamed(scene, "cb_light");
  EXPECT_NEAR(light.emissive.x, 17.0f, 1e-3f);
  EXPECT_NEAR(light.emissive.y, 12.0f, 1e-3f);
  EXPECT_NEAR(light.emissive.z, 4.0f, 1e-3f);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_NEAR(glm::distance(scene.camera->position, glm::vec3(0.278f, 0.273f, -0.8f)), 0.0f, 1e-6f);
  glm::vec3 forward = glm::normalize(scene.camera->target - scene.camera->position);
  EXPECT_NEAR(glm::distance(forward, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(scene.camera->up, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(scene.camera->verticalFovDegrees, 39.3077f, 1e-3f);
  EXPECT_TRUE(scene.images.empty());
}

TEST(SharedScenes, GlassVaseFlowers) {
  const Scene& scene = sharedScene("glass_vase_flowers/glTF/GlassVaseFlowers.gltf");
  EXPECT_GT(scene.instances.size(), scene.meshes.size());  // the flowers are instanced
  EXPECT_EQ(scene.uniqueTriangleCount(), 10218u);
  EXPECT_EQ(scene.triangleCount(), 14036u);
  const Material& flowers = materialNamed(scene, "Flowers");
  EXPECT_EQ(flowers.alphaMode, AlphaMode::Mask);
  EXPECT_TRUE(flowers.doubleSided);
  ASSERT_GE(flowers.baseColorTexture, 0);
  const Image& albedo = scene.images[size_t(flowers.baseColorTexture)];
  EXPECT_EQ(albedo.width, 1024);
  EXPECT_EQ(materialNamed(scene, "GlassAlpha").alphaMode, AlphaMode::Blend);
}

TEST(SharedScenes, SheenChair) {
  const Scene& scene = sharedScene("sheen_chair/glTF/SheenChair.gltf");
  EXPECT_EQ(scene.uniqueTriangleCount(), 39936u);
  EXPECT_FALSE(scene.images.empty());
  for (const Image& image : scene.images)
    EXPECT_EQ(image.rgba.size(), size_t(image.width) * image.height * 4);
}

TEST(SharedScenes, DamagedHelmet) {
  const Scene& scene = sharedScene("damaged_helmet/glTF/DamagedHelmet.gltf");
  EXPECT_EQ(scene.triangleCount(), 15452u);
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_GE(m.baseColorTexture, 0);
  EXPECT_GE(m.metallicRoughnessTexture, 0);
  EXPECT_GE(m.normalTexture, 0);
  EXPECT_GE(m.emissiveTexture, 0);
  EXPECT_EQ(scene.images.size(), 4u);  // the occlusion map is not used, so not decoded
  const Geometry& g = scene.meshes[0].geometries[0];
  EXPECT_EQ(g.tangents.size(), 0u);  // the file has none
  EXPECT_EQ(g.uvs.size(), g.positions.size());
}

TEST(SharedScenes, EmissiveStrength) {
  const Scene& scene = sharedScene("emissive_strength_test/glTF/EmissiveStrengthTest.gltf");
  EXPECT_EQ(scene.triangleCount(), 90u);
  const Material& m = materialNamed(scene, "Emit16");
  EXPECT_NEAR(m.emissive.x, 1.6f, 1e-5f);
  EXPECT_NEAR(m.emissive.y, 8.0f, 1e-5f);
  EXPECT_NEAR(m.emissive.z, 14.4f, 1e-5f);
  EXPECT_NEAR(materialNamed(scene, "Emit1").emissive.z, 0.9f, 1e-6f);
}

// glTF node animations become SceneAnimation tracks (src/scene/gltf_animation.cpp): a parent
// node (static, baked) with an animated child quad; LINEAR translation, STEP rotation.
TEST_F(GltfLoaderTest, NodeAnimationsBecomeTransformTracks) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  int mesh = w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  int child = w.addNode({{"mesh", mesh}, {"scale", {2, 2, 2}}}, false);
  w.addNode({{"translation", {0, 0, -5}}, {"children", {child}}});
  const float times[] = {0.0f, 2.0f};
  const float translations[] = {0, 0, 0, 4, 0, 0};
  const float rotations[] = {0, 0, 0, 1, 0, 0.70710678f, 0, 0.70710678f};  // x, y, z, w
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int t = w.addAccessor(w.addView(translations, sizeof(translations)), kFloat, 2, "VEC3");
  int r = w.addAccessor(w.addView(rotations, sizeof(rotations)), kFloat, 2, "VEC4");
  w.doc["animations"] =
      json::array({{{"samplers",
                     {{{"input", in}, {"output", t}},
                      {{"input", in}, {"output", r}, {"interpolation", "STEP"}}}},
                    {"channels",
                     {{{"sampler", 0}, {"target", {{"node", child}, {"path", "translation"}}}},
                      {{"sampler", 1}, {"target", {{"node", child}, {"path", "rotation"}}}}}}}});
  Scene scene = loadGltf(w.writeGltf(dir, "animated"));
  ASSERT_EQ(scene.animation.transforms.size(), 1u);
  EXPECT_FLOAT_EQ(scene.animation.transformDuration(), 2.0f);
  std::vector<glm::mat4> transforms = {scene.instances[0].transform};
  evaluateTransforms(scene.animation, 0.0f, {}, transforms);
  EXPECT_LT(glm::length(glm::vec3(transforms[0][3]) - glm::vec3(0, 0, -5)), 1e-5f);
  EXPECT_NEAR(transforms[0][0][0], 2.0f, 1e-5f);  // rest scale kept, no rotation yet
  evaluateTransforms(scene.animation, 1.0f, {}, transforms);
  EXPECT_LT(glm::length(glm::vec3(transforms[0][3]) - glm::vec3(2, 0, -5)), 1e-5f);
  EXPECT_NEAR(transforms[0][0][0], 2.0f, 1e-5f);  // STEP: still the first rotation
  evaluateTransforms(scene.animation, 1.999f, {}, transforms);
  EXPECT_NEAR(transforms[0][0][2], 0.0f, 1e-5f);
  SceneAnimation held = scene.animation;
  held.loop = false;
  evaluateTransforms(held, 2.0f, {}, transforms);  // the last key: 90 degrees about +Y
  EXPECT_NEAR(transforms[0][0][2], -2.0f, 1e-4f);
}

TEST_F(GltfLoaderTest, CubicSplineAnimationIsAClearError) {
  GltfWriter w;
  w.addQuadScene();
  const float times[] = {0.0f, 1.0f};
  const float values[18] = {};
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(values, sizeof(values)), kFloat, 6, "VEC3");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}, {"interpolation", "CUBICSPLINE"}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}});
  expectError(w.writeGltf(dir, "cubic"), "CUBICSPLINE");
}

}  // namespace
}  // namespace bounce
