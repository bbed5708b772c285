#include "scene/gltf_accessor.h"

#include <tiny_gltf.h>
#include <cstring>

#include "core/error.h"

namespace bounce::gltf {
namespace {

// Component sizes of the types glTF 2.0 allows in accessors; 0 for anything else (tinygltf also
// accepts INT and DOUBLE, which glTF forbids).
size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

size_t componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "unknown";
  }
}

bool isUnsignedIntegerType(int componentType) {
  return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// Bytes are copied out with memcpy because glTF only promises alignment to the component size
// relative to the buffer start, and buffers may sit anywhere in the loaded file.
template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// glTF 2.0 §3.11: normalized signed values map c -> max(c / MAX, -1), unsigned c -> c / MAX.
float componentAsFloat(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      float c = load<int8_t>(p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      float c = load<uint8_t>(p);
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      float c = load<int16_t>(p);
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      float c = load<uint16_t>(p);
      return normalized ? c / 65535.0f : c;
    }
    default: {
      float c = float(load<uint32_t>(p));
      return normalized ? c / 4294967295.0f : c;
    }
  }
}

uint32_t componentAsUnsigned(const uint8_t* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load<uint16_t>(p);
    default:
      return load<uint32_t>(p);
  }
}

// `count` elements of `elementSize` bytes, `stride` apart, all inside the file's data.
struct ElementRun {
  const uint8_t* data = nullptr;
  size_t stride = 0;
  size_t count = 0;
  const uint8_t* element(size_t i) const { return data + i * stride; }
};

// Locates `count` elements starting `byteOffset` bytes into buffer view `viewIndex` and checks
// that the last one ends inside the view. Sparse index/value views must be tightly packed, so
// they pass useViewStride = false.
ElementRun elementRun(const Source& src, int viewIndex, size_t byteOffset, size_t count,
                      size_t elementSize, bool useViewStride, const std::string& what) {
  std::span<const uint8_t> bytes = bufferViewBytes(src, viewIndex, what);
  const tinygltf::BufferView& view = src.model.bufferViews[size_t(viewIndex)];
  size_t stride = useViewStride && view.byteStride != 0 ? view.byteStride : elementSize;
  if (stride < elementSize)
    fail("{}: {}: bufferView {} has byteStride {}, smaller than the element size {}", src.path,
         what, viewIndex, stride, elementSize);
  ElementRun run{bytes.data(), stride, count};
  if (count == 0) return run;
  // count <= 2^28 and stride <= 252, so this sum cannot overflow 64 bits once the offset is
  // known to lie inside the view.
  uint64_t end = byteOffset > bytes.size()
                     ? UINT64_MAX
                     : uint64_t(byteOffset) + uint64_t(stride) * (count - 1) + elementSize;
  if (end > bytes.size())
    fail(
        "{}: {}: {} elements of {} bytes (stride {}) from offset {} exceed bufferView {} "
        "({} bytes); the accessor must lie inside its bufferView",
        src.path, what, count, elementSize, stride, byteOffset, viewIndex, bytes.size());
  run.data += byteOffset;
  return run;
}

// Where an accessor's elements come from, fully range-checked before anything is allocated:
// the dense base run (absent when the accessor has no bufferView: zeros), and the sparse
// substitutions (index run + value run).
struct AccessorPlan {
  const tinygltf::Accessor* accessor = nullptr;
  size_t componentSize = 0;
  size_t components = 0;
  ElementRun base;
  ElementRun sparseIndices;
  ElementRun sparseValues;
  int sparseIndexType = 0;
};

const tinygltf::Accessor& accessorAt(const Source& src, int index, const std::string& what) {
  if (index < 0 || size_t(index) >= src.model.accessors.size())
    fail("{}: {} refers to accessor {} ({} accessors)", src.path, what, index,
         src.model.accessors.size());
  return src.model.accessors[size_t(index)];
}

void planSparse(const Source& src, AccessorPlan& plan, const std::string& what) {
  const tinygltf::Accessor& a = *plan.accessor;
  const auto& sparse = a.sparse;
  if (sparse.count < 0 || size_t(sparse.count) > a.count)
    fail("{}: {}: sparse count {} must be between 0 and the accessor count {}", src.path, what,
         sparse.count, a.count);
  if (!isUnsignedIntegerType(sparse.indices.componentType))
    fail(
        "{}: {}: sparse indices have componentType {}, expected UNSIGNED_BYTE, "
        "UNSIGNED_SHORT or UNSIGNED_INT",
        src.path, what, sparse.indices.componentType);
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    fail("{}: {}: negative sparse byteOffset", src.path, what);
  size_t elementSize = plan.componentSize * plan.components;
  plan.sparseIndexType = sparse.indices.componentType;
  plan.sparseIndices = elementRun(src, sparse.indices.bufferView, size_t(sparse.indices.byteOffset),
                                  size_t(sparse.count), componentSize(plan.sparseIndexType), false,
                                  what + " sparse indices");
  plan.sparseValues = elementRun(src, sparse.values.bufferView, size_t(sparse.values.byteOffset),
                                 size_t(sparse.count), elementSize, false, what + " sparse values");
  for (size_t k = 0; k < size_t(sparse.count); ++k) {
    uint32_t target = componentAsUnsigned(plan.sparseIndices.element(k), plan.sparseIndexType);
    if (target >= a.count)
      fail("{}: {}: sparse index {} out of range (accessor count {})", src.path, what, target,
           a.count);
  }
}

AccessorPlan planAccessor(const Source& src, int index, int expectedType, const std::string& use) {
  const tinygltf::Accessor& a = accessorAt(src, index, use);
  std::string what = fmt::format("accessor {} ({})", index, use);
  if (a.type != expectedType)
    fail("{}: {} has type {}, expected {}", src.path, what, typeName(a.type),
         typeName(expectedType));
  AccessorPlan plan{&a, componentSize(a.componentType), componentCount(a.type)};
  if (plan.componentSize == 0)
    fail("{}: {} has componentType {}, which glTF 2.0 does not allow", src.path, what,
         a.componentType);
  if (a.count > kMaxAccessorCount)
    fail("{}: {}: count {} exceeds the limit of 2^28 elements", src.path, what, a.count);
  if (a.bufferView >= 0) {
    plan.base = elementRun(src, a.bufferView, a.byteOffset, a.count,
                           plan.componentSize * plan.components, true, what);
  } else if (a.count > kMaxUnbackedAccessorCount) {
    fail("{}: {}: count {} without a bufferView exceeds the limit of 2^20 elements", src.path, what,
         a.count);
  }
  if (a.sparse.isSparse) planSparse(src, plan, what);
  return plan;
}

// Calls store(elementIndex, elementBytes) for each base element, then for each sparse
// substitution, so later writes override the base as the spec requires.
template <typename Store>
void forEachElement(const AccessorPlan& plan, const Store& store) {
  for (size_t i = 0; i < plan.base.count; ++i) store(i, plan.base.element(i));
  for (size_t k = 0; k < plan.sparseValues.count; ++k)
    store(componentAsUnsigned(plan.sparseIndices.element(k), plan.sparseIndexType),
          plan.sparseValues.element(k));
}

}  // namespace

std::span<const uint8_t> bufferViewBytes(const Source& src, int index, const std::string& what) {
  const tinygltf::Model& m = src.model;
  if (index < 0 || size_t(index) >= m.bufferViews.size())
    fail("{}: {} refers to bufferView {} ({} bufferViews)", src.path, what, index,
         m.bufferViews.size());
  const tinygltf::BufferView& view = m.bufferViews[size_t(index)];
  if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
    fail("{}: bufferView {} refers to buffer {} ({} buffers)", src.path, index, view.buffer,
         m.buffers.size());
  const std::vector<unsigned char>& data = m.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("{}: bufferView {} (offset {}, length {}) lies outside buffer {} ({} bytes)", src.path,
         index, view.byteOffset, view.byteLength, view.buffer, data.size());
  return {data.data() + view.byteOffset, view.byteLength};
}

std::vector<float> readFloatAccessor(const Source& src, int index, int expectedType,
                                     const std::string& what) {
  AccessorPlan plan = planAccessor(src, index, expectedType, what);
  const tinygltf::Accessor& a = *plan.accessor;
  std::vector<float> out(a.count * plan.components, 0.0f);
  forEachElement(plan, [&](size_t i, const uint8_t* p) {
    for (size_t c = 0; c < plan.components; ++c)
      out[i * plan.components + c] =
          componentAsFloat(p + c * plan.componentSize, a.componentType, a.normalized);
  });
  return out;
}

std::vector<uint32_t> readIndexAccessor(const Source& src, int index, const std::string& what) {
  AccessorPlan plan = planAccessor(src, index, TINYGLTF_TYPE_SCALAR, what);
  const tinygltf::Accessor& a = *plan.accessor;
  if (!isUnsignedIntegerType(a.componentType))
    fail(
        "{}: accessor {} ({}) has componentType {}, expected UNSIGNED_BYTE, UNSIGNED_SHORT or "
        "UNSIGNED_INT",
        src.path, index, what, a.componentType);
  std::vector<uint32_t> out(a.count, 0u);
  forEachElement(
      plan, [&](size_t i, const uint8_t* p) { out[i] = componentAsUnsigned(p, a.componentType); });
  return out;
}

}  // namespace bounce::gltf
