// Declaring a frame: resources, passes and their accesses. Mistakes that can be caught at the
// call are reported there, naming the pass and resource.
#include "graph/frame_graph.h"

#include <algorithm>

#include "core/error.h"

namespace bounce::graph {

ImportedImage ImportedImage::from(const vk::Image& image, VkImageLayout currentLayout) {
  return {image.handle(), image.view(), image.format(), {image.width(), image.height()},
          image.layers(), image.mips(), currentLayout};
}

ImportedBuffer ImportedBuffer::from(const vk::Buffer& buffer) {
  return {buffer.handle(), buffer.size(), buffer.address(), buffer.mapped()};
}

// ---- resources ------------------------------------------------------------------------------

void FrameGraph::beginFrame() {
  resources_.clear();
  passes_.clear();
  declaredResources_ = declaredPasses_ = 0;
  compiled_ = false;
}

// Names identify passes and resources in timings, debug views and errors, so each is unique
// among its kind (a pass may share its name with the resource it writes).
void FrameGraph::checkNewResourceName(const std::string& name) const {
  if (name.empty()) fail("frame graph: a resource needs a name");
  for (const ResourceDecl& r : resources_)
    if (r.name == name) fail("frame graph: resource '{}' declared twice", name);
}

void FrameGraph::checkNewPassName(const std::string& name) const {
  if (name.empty()) fail("frame graph: a pass needs a name");
  for (const PassDecl& p : passes_)
    if (p.name == name) fail("frame graph: pass '{}' declared twice", name);
}

uint32_t FrameGraph::declareResource(ResourceDecl decl) {
  removeInternalDeclarations();
  if (decl.group.empty()) decl.group = decl.name;
  resources_.push_back(std::move(decl));
  declaredResources_ = resources_.size();
  compiled_ = false;
  return uint32_t(resources_.size() - 1);
}

ImageHandle FrameGraph::createImage(const std::string& name, const ImageDesc& desc) {
  checkNewResourceName(name);
  checkImageDesc(name, desc);
  return {declareResource(
      {.name = name, .kind = ResourceKind::Transient, .isImage = true, .image = desc})};
}

ImageHandle FrameGraph::createPersistentImage(const std::string& name, const ImageDesc& desc) {
  checkNewResourceName(name);
  checkImageDesc(name, desc);
  return {declareResource(
      {.name = name, .kind = ResourceKind::Persistent, .isImage = true, .image = desc})};
}

HistoryImage FrameGraph::createHistoryImage(const std::string& name, const ImageDesc& desc) {
  std::string previousName = name + ".previous";
  checkNewResourceName(name);
  checkNewResourceName(previousName);
  checkImageDesc(name, desc);
  history_[name];  // a new history starts invalid
  ResourceDecl current{.name = name,
                       .kind = ResourceKind::History,
                       .isImage = true,
                       .image = desc,
                       .role = HistoryRole::Current,
                       .group = name};
  ResourceDecl previous = current;
  previous.name = previousName;
  previous.role = HistoryRole::Previous;
  HistoryImage history;
  history.current = {declareResource(std::move(current))};
  history.previous = {declareResource(std::move(previous))};
  return history;
}

ImageHandle FrameGraph::importImage(const std::string& name, const ImportedImage& image) {
  checkNewResourceName(name);
  if (!image.image || !image.view) fail("imported image '{}': no VkImage or view", name);
  ImageDesc desc{image.format, ImageSize::fixed(image.extent.width, image.extent.height),
                 image.layers, image.mips};
  checkImageDesc(name, desc);
  return {declareResource({.name = name,
                           .kind = ResourceKind::Imported,
                           .isImage = true,
                           .image = desc,
                           .importedImage = image})};
}

BufferHandle FrameGraph::createBuffer(const std::string& name, const BufferDesc& desc) {
  checkNewResourceName(name);
  checkBufferDesc(name, desc);
  return {declareResource({.name = name, .kind = ResourceKind::Transient, .buffer = desc})};
}

BufferHandle FrameGraph::createPersistentBuffer(const std::string& name, const BufferDesc& desc) {
  checkNewResourceName(name);
  checkBufferDesc(name, desc);
  return {declareResource({.name = name, .kind = ResourceKind::Persistent, .buffer = desc})};
}

HistoryBuffer FrameGraph::createHistoryBuffer(const std::string& name, const BufferDesc& desc) {
  std::string previousName = name + ".previous";
  checkNewResourceName(name);
  checkNewResourceName(previousName);
  checkBufferDesc(name, desc);
  history_[name];  // a new history starts invalid
  ResourceDecl current{.name = name,
                       .kind = ResourceKind::History,
                       .buffer = desc,
                       .role = HistoryRole::Current,
                       .group = name};
  ResourceDecl previous = current;
  previous.name = previousName;
  previous.role = HistoryRole::Previous;
  HistoryBuffer history;
  history.current = {declareResource(std::move(current))};
  history.previous = {declareResource(std::move(previous))};
  return history;
}

BufferHandle FrameGraph::importBuffer(const std::string& name, const ImportedBuffer& buffer) {
  checkNewResourceName(name);
  if (!buffer.buffer || buffer.size == 0)
    fail("imported buffer '{}': no VkBuffer or zero size", name);
  BufferDesc desc{BufferSize::fixed(buffer.size),
                  buffer.mapped ? vk::MemoryUse::Readback : vk::MemoryUse::DeviceOnly};
  return {declareResource(
      {.name = name, .kind = ResourceKind::Imported, .buffer = desc, .importedBuffer = buffer})};
}

const FrameGraph::ResourceDecl& FrameGraph::resourceDecl(uint32_t index,
                                                         const char* expected) const {
  if (index >= resources_.size())
    fail("frame graph: {} handle {} is not from this frame's declarations", expected,
         index == kNoResource ? std::string("(none)") : std::to_string(index));
  return resources_[index];
}

// Resources keep their GPU objects and states across frames under this key. The two sides of a
// history swap keys every frame; imported resources live in their own namespace.
std::string FrameGraph::physicalKey(const ResourceDecl& resource) const {
  switch (resource.kind) {
    case ResourceKind::Imported:
      return "import:" + resource.name;
    case ResourceKind::History: {
      uint32_t parity = history_.at(resource.group).parity;
      uint32_t side = resource.role == HistoryRole::Current ? parity : 1 - parity;
      return resource.group + "#" + std::to_string(side);
    }
    default:
      return resource.name;
  }
}

bool FrameGraph::historyValid(const HistoryImage& history) const {
  return history_.at(resourceDecl(history.current.index, "image").group).valid;
}

bool FrameGraph::historyValid(const HistoryBuffer& history) const {
  return history_.at(resourceDecl(history.current.index, "buffer").group).valid;
}

void FrameGraph::resetHistory() {
  for (auto& [name, info] : history_) info.valid = false;
}

// ---- passes ---------------------------------------------------------------------------------

PassBuilder FrameGraph::addPass(const std::string& name, QueueKind kind) {
  checkNewPassName(name);
  removeInternalDeclarations();
  passes_.push_back({.name = name, .kind = kind});
  declaredPasses_ = passes_.size();
  compiled_ = false;
  return PassBuilder(*this, uint32_t(passes_.size() - 1));
}

PassBuilder& PassBuilder::read(ImageHandle image, Access access) {
  graph_.resourceDecl(image.index, "image");
  return use(image.index, access, false);
}

PassBuilder& PassBuilder::read(BufferHandle buffer, Access access) {
  graph_.resourceDecl(buffer.index, "buffer");
  return use(buffer.index, access, false);
}

PassBuilder& PassBuilder::write(ImageHandle image, Access access) {
  graph_.resourceDecl(image.index, "image");
  return use(image.index, access, true);
}

PassBuilder& PassBuilder::write(BufferHandle buffer, Access access) {
  graph_.resourceDecl(buffer.index, "buffer");
  return use(buffer.index, access, true);
}

PassBuilder& PassBuilder::read(ImageHandle image, Access access, uint32_t binding) {
  graph_.resourceDecl(image.index, "image");
  return use(image.index, access, false, binding);
}

PassBuilder& PassBuilder::write(ImageHandle image, Access access, uint32_t binding) {
  graph_.resourceDecl(image.index, "image");
  return use(image.index, access, true, binding);
}

PassBuilder& PassBuilder::readPlaceholder(ImageHandle image, uint32_t binding, Access access) {
  graph_.resourceDecl(image.index, "image");
  if (access != Access::StorageRead && access != Access::SampledRead)
    fail("pass '{}': placeholder '{}' at binding {} must be a StorageRead or SampledRead",
         graph_.passes_[pass_].name, graph_.resources_[image.index].name, binding);
  use(image.index, access, false);
  FrameGraph::PassDecl& pass = graph_.passes_[pass_];
  for (const FrameGraph::ResourceUse& other : pass.uses)
    if (other.binding == binding)
      fail("pass '{}' binds '{}' and placeholder '{}' both at binding {}", pass.name,
           graph_.resources_[other.resource].name, graph_.resources_[image.index].name, binding);
  pass.placeholders.push_back({image.index, binding});
  return *this;
}

PassBuilder& PassBuilder::sideEffects() {
  graph_.passes_[pass_].sideEffects = true;
  return *this;
}

PassBuilder& PassBuilder::record(RecordFn callback) {
  graph_.passes_[pass_].record = std::move(callback);
  return *this;
}

// One declaration per resource and pass: two reads in the same layout merge (a texture read in
// the vertex and fragment stages); anything else is ambiguous about layout or ordering.
PassBuilder& PassBuilder::use(uint32_t resource, Access access, bool asWrite, uint32_t binding) {
  FrameGraph::PassDecl& pass = graph_.passes_[pass_];
  const FrameGraph::ResourceDecl& decl = graph_.resources_[resource];
  AccessInfo info = accessInfo(access, pass.kind);
  if (info.writes != asWrite)
    fail("pass '{}': {} of '{}' is a {}; use {}()", pass.name, accessName(access), decl.name,
         info.writes ? "write" : "read", info.writes ? "write" : "read");
  if (decl.isImage ? !info.onImages : !info.onBuffers)
    fail("pass '{}': {} does not apply to {} '{}'", pass.name, accessName(access),
         decl.isImage ? "image" : "buffer", decl.name);
  if (decl.role == FrameGraph::HistoryRole::Previous && info.writes)
    fail("pass '{}' writes '{}': the previous frame's history is read-only; write '{}'", pass.name,
         decl.name, decl.group);
  for (const FrameGraph::ResourceUse& other : pass.uses)
    if (binding != kNoBinding && other.binding == binding && other.resource != resource)
      fail("pass '{}' binds '{}' and '{}' both at binding {}", pass.name,
           graph_.resources_[other.resource].name, decl.name, binding);
  for (FrameGraph::ResourceUse& earlier : pass.uses) {
    if (earlier.resource != resource) continue;
    if (binding != kNoBinding && earlier.binding != kNoBinding && earlier.binding != binding)
      fail("pass '{}' binds '{}' twice (bindings {} and {}): one image, one binding", pass.name,
           decl.name, earlier.binding, binding);
    bool mergeable = !info.writes && !earlier.info.writes &&
                     (!decl.isImage || earlier.info.layout == info.layout);
    if (!mergeable)
      fail(
          "pass '{}' declares '{}' twice ({} and {}): declare one access (StorageReadWrite for "
          "read-modify-write)",
          pass.name, decl.name, accessName(earlier.access), accessName(access));
    earlier.info.stages |= info.stages;
    earlier.info.access |= info.access;
    earlier.mergedReads.push_back(access);
    if (binding != kNoBinding) earlier.binding = binding;
    return *this;
  }
  pass.uses.push_back({resource, access, info, binding});
  return *this;
}

}  // namespace bounce::graph
