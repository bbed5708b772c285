// Builds small glTF 2.0 files for the tests: a JSON document plus one binary buffer, written as
// .gltf + .bin, as a .gltf with a data-URI buffer, or as .glb.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace bounce::test {

inline constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;

class GltfWriter {
 public:
  using json = nlohmann::json;

  GltfWriter() {
    doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0},
           {"scenes", json::array()},       {"nodes", json::array()},
           {"meshes", json::array()},       {"accessors", json::array()},
           {"bufferViews", json::array()},  {"buffers", json::array()}};
  }

  // Appends bytes (4-byte aligned) and a bufferView over them.
  int addView(const void* data, size_t bytes, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (stride) view["byteStride"] = stride;
    bin.insert(bin.end(), static_cast<const uint8_t*>(data),
               static_cast<const uint8_t*>(data) + bytes);
    doc["bufferViews"].push_back(view);
    return int(doc["bufferViews"].size()) - 1;
  }

  int addAccessor(int view, int componentType, size_t count, const char* type) {
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return int(doc["accessors"].size()) - 1;
  }

  int addPositions(const std::vector<glm::vec3>& p) {
    return addAccessor(addView(p.data(), p.size() * 12), kFloat, p.size(), "VEC3");
  }
  int addUvs(const std::vector<glm::vec2>& uv) {
    return addAccessor(addView(uv.data(), uv.size() * 8), kFloat, uv.size(), "VEC2");
  }
  int addIndices16(const std::vector<uint16_t>& i) {
    return addAccessor(addView(i.data(), i.size() * 2), kUnsignedShort, i.size(), "SCALAR");
  }

  // A mesh of one primitive; returns the mesh index.
  int addMesh(json primitive) {
    doc["meshes"].push_back({{"primitives", json::array({primitive})}});
    return int(doc["meshes"].size()) - 1;
  }

  int addNode(json node, bool root = true) {
    doc["nodes"].push_back(node);
    int index = int(doc["nodes"].size()) - 1;
    if (root) rootNodes.push_back(index);
    return index;
  }

  // The unit quad in the XY plane (two triangles), one node, one scene.
  void addQuadScene() {
    int pos = addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    int idx = addIndices16({0, 1, 2, 0, 2, 3});
    addNode({{"mesh", addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  }

  std::string writeGltf(const std::string& dir, const std::string& name) {
    finish(name + ".bin");
    writeBytes(dir + "/" + name + ".bin", bin);
    return writeText(dir + "/" + name + ".gltf", doc.dump());
  }

  std::string writeGltfDataUri(const std::string& dir, const std::string& name) {
    finish("data:application/octet-stream;base64," + base64(bin));
    return writeText(dir + "/" + name + ".gltf", doc.dump());
  }

  std::string writeGlb(const std::string& dir, const std::string& name) {
    finish("");
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942);
    out.insert(out.end(), bin.begin(), bin.end());
    std::string path = dir + "/" + name + ".glb";
    writeBytes(path, out);
    return path;
  }

  static void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }
  static std::string writeText(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  json doc;
  std::vector<uint8_t> bin;
  std::vector<int> rootNodes;

 private:
  void finish(const std::string& bufferUri) {
    json buffer = {{"byteLength", bin.size()}};
    if (!bufferUri.empty()) buffer["uri"] = bufferUri;
    if (doc["buffers"].empty()) doc["buffers"].push_back(buffer);
    if (doc["scenes"].empty()) doc["scenes"].push_back({{"nodes", rootNodes}});
  }

  static std::string base64(const std::vector<uint8_t>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
      uint32_t n = uint32_t(data[i]) << 16;
      if (i + 1 < data.size()) n |= uint32_t(data[i + 1]) << 8;
      if (i + 2 < data.size()) n |= data[i + 2];
      out += table[(n >> 18) & 63];
      out += table[(n >> 12) & 63];
      out += i + 1 < data.size() ? table[(n >> 6) & 63] : '=';
      out += i + 2 < data.size() ? table[n & 63] : '=';
    }
    return out;
  }
};

}  // namespace bounce::test
