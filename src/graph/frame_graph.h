// The frame graph. Every frame the renderer declares its passes in one straight-line function:
// each pass has a stable name, a queue kind, the images and buffers it reads and writes, and a
// callback that records its commands. From those declarations the graph culls passes whose
// output nobody reads, derives every barrier (synchronization2), times and labels each pass,
// keeps history resources across frames (ping-pong) and copies any pass's output back to the
// host as a debug view. Resources are created by allocate() at init and on resize, never by a
// frame (DESIGN.md §1).
//
//   graph.beginFrame();
//   ImageHandle normal = graph.createImage("gbuffer.normal", {VK_FORMAT_R16G16B16A16_SFLOAT});
//   HistoryImage color = graph.createHistoryImage("taa.color", {VK_FORMAT_R16G16B16A16_SFLOAT});
//   graph.addPass("gbuffer", QueueKind::Compute)
//       .write(normal, Access::StorageWrite)
//       .record([&](VkCommandBuffer cmd, const PassResources& r) { gbuffer.record(cmd, r); });
//   graph.addPass("taa", QueueKind::Compute)
//       .read(normal, Access::SampledRead)
//       .read(color.previous, Access::SampledRead)
//       .write(color.current, Access::StorageWrite)
//       .record([&](VkCommandBuffer cmd, const PassResources& r) { taa.record(cmd, r, color); });
//   graph.allocate(context, resolution);  // first frame and after a resize only
//   graph.execute(cmd, &timer);           // compiles, records, ends the frame
//
// Declaring and compile() need no GPU; tests drive them with endFrame() instead of execute().
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "graph/access.h"
#include "graph/frame_plan.h"
#include "graph/handles.h"
#include "graph/pass_resources.h"
#include "graph/resource_desc.h"
#include "vk/context.h"
#include "vk/gpu_timer.h"
#include "vk/resources.h"

namespace bounce::graph {

using RecordFn = std::function<void(VkCommandBuffer, const PassResources&)>;

// An image owned outside the graph. `layout` is its layout when first imported; from then on the
// graph tracks it, as long as the same VkImage is imported under the same name.
struct ImportedImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  uint32_t layers = 1;
  uint32_t mips = 1;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  // The owner writes it between frames (a host's G-buffer): every frame it starts in `layout`
  // behind a barrier from any earlier write on the queue (ALL_COMMANDS, MEMORY_WRITE), rather
  // than where the graph left it.
  bool externalWrites = false;

  static ImportedImage from(const vk::Image& image, VkImageLayout currentLayout);
};

// A buffer owned outside the graph. A mapped buffer is read by the host: what a frame writes to
// it is made visible to the host at the end of the frame.
struct ImportedBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  VkDeviceAddress address = 0;
  void* mapped = nullptr;

  static ImportedBuffer from(const vk::Buffer& buffer);
};

// A debug view read back after its frame completed: the texels of mip 0 (every layer, rows top
// to bottom, tightly packed) or the bytes of a buffer.
struct DebugView {
  std::string name;      // as requested: a pass or a resource
  std::string resource;  // what was copied
  bool isImage = false;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0, layers = 0;
  uint64_t frame = 0;  // the frame it shows
  std::vector<std::byte> bytes;
};

class FrameGraph;

// Declares one pass's accesses; returned by FrameGraph::addPass.
class PassBuilder {
 public:
  PassBuilder(FrameGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
  PassBuilder& read(ImageHandle image, Access access);
  PassBuilder& read(BufferHandle buffer, Access access);
  PassBuilder& write(ImageHandle image, Access access);
  PassBuilder& write(BufferHandle buffer, Access access);
  // The same, and the image is bound to the pass's shader at `binding` (a storage image of set
  // 1; the binding constants live in the pass's shaders/shared/*_io.h). The pass's record
  // callback finds every bound image in PassResources::boundImages(): an image is named once
  // in C++, where it is declared, and once in GLSL.
  PassBuilder& read(ImageHandle image, Access access, uint32_t binding);
  PassBuilder& write(ImageHandle image, Access access, uint32_t binding);
  // Fills `binding` with `image` where the shader ignores that binding in this configuration
  // (its producer pass is off): a read of `image` (StorageRead, or SampledRead for a sampled
  // binding), merged with the pass's other read of it if any. The one way an image sits at two
  // bindings; declare a real access with read().
  PassBuilder& readPlaceholder(ImageHandle image, uint32_t binding,
                               Access access = Access::StorageRead);
  // Keeps the pass even when nothing reads what it writes (it talks to the host, say).
  PassBuilder& sideEffects();
  PassBuilder& record(RecordFn callback);

 private:
  PassBuilder& use(uint32_t resource, Access access, bool asWrite, uint32_t binding = kNoBinding);
  FrameGraph& graph_;
  uint32_t pass_;
};

class FrameGraph {
 public:
  FrameGraph() = default;
  ~FrameGraph();  // waits for the device before destroying its resources
  FrameGraph(const FrameGraph&) = delete;
  FrameGraph& operator=(const FrameGraph&) = delete;

  // ---- declaring a frame (CPU only) ------------------------------------------------------
  // Forgets the last frame's passes and resource declarations; GPU resources, their states,
  // history and debug-view requests stay. Without it, the last declarations run again.
  void beginFrame();
  [[nodiscard]] ImageHandle createImage(const std::string& name, const ImageDesc& desc);
  [[nodiscard]] ImageHandle createPersistentImage(const std::string& name, const ImageDesc& desc);
  [[nodiscard]] HistoryImage createHistoryImage(const std::string& name, const ImageDesc& desc);
  [[nodiscard]] ImageHandle importImage(const std::string& name, const ImportedImage& image);
  [[nodiscard]] BufferHandle createBuffer(const std::string& name, const BufferDesc& desc);
  [[nodiscard]] BufferHandle createPersistentBuffer(const std::string& name,
                                                    const BufferDesc& desc);
  [[nodiscard]] HistoryBuffer createHistoryBuffer(const std::string& name, const BufferDesc& desc);
  [[nodiscard]] BufferHandle importBuffer(const std::string& name, const ImportedBuffer& buffer);
  PassBuilder addPass(const std::string& name, QueueKind kind);

  // False in a history's first frame and after resetHistory(): `previous` holds nothing useful
  // (it is zeroed when allocated, so reading it is safe, merely meaningless).
  bool historyValid(const HistoryImage& history) const;
  bool historyValid(const HistoryBuffer& history) const;
  // After a camera cut or a resize: every history's `previous` is invalid in the next frame.
  void resetHistory();

  // ---- debug views ------------------------------------------------------------------------
  // A pass name shows the first image (else buffer) the pass writes, copied right after it; a
  // resource name (a history's name means its `current`) shows it at the end of the frame.
  // Names are checked by compile(); the readback buffer is created by the next allocate().
  void requestDebugView(const std::string& passOrResource);
  void clearDebugViews();
  // Call once the frame's submission has completed.
  DebugView readDebugView(const std::string& name) const;

  // ---- compiling (CPU only) ---------------------------------------------------------------
  // Validates the declarations, culls passes nobody needs, derives barriers. Throws
  // bounce::Error naming the pass and resource at fault.
  const FramePlan& compile();
  const FramePlan& plan() const { return plan_; }
  // The CPU side of the end of a frame: commits resource states and swaps history. execute()
  // calls it; tests without a GPU call it instead.
  void endFrame();
  uint64_t frameIndex() const { return frameIndex_; }
  // The names this frame declared (the graph's own debug-view passes and readbacks left out):
  // what --view and requestDebugView() accept.
  std::vector<std::string> declaredPassNames() const;
  std::vector<std::string> declaredResourceNames() const;
  // The compiled plan as text: passes, barriers, culled passes.
  std::string describe() const;

  // ---- GPU --------------------------------------------------------------------------------
  // Creates every resource this frame's declarations need that does not exist yet with the same
  // size, format and usage; a no-op when nothing changed. Call after declaring the first frame,
  // on resize (history is reset), and after requesting a debug view. Persistent and history
  // resources start zeroed. Waits for the device before replacing anything.
  void allocate(vk::Context& context, VkExtent2D renderResolution);
  // Records every pass: its barriers, a GPU timestamp scope and a debug label named after it,
  // then its callback. Ends the frame (history swaps). Fails if allocate() is needed.
  void execute(VkCommandBuffer cmd, vk::GpuTimer* timer = nullptr);
  // The same frame as execute(), but each pass in a command buffer of its own, submitted and
  // waited for, its host wall and process CPU time logged (vk/pipeline_log.h). What a pass
  // costs the first time it runs is then visible: on a CPU device (lavapipe), compiling its
  // shaders happens at its first dispatch, not at pipeline creation (docs/startup.md).
  void executePassByPass(vk::GpuTimer* timer = nullptr);
  VkExtent2D renderResolution() const { return resolution_; }
  // After execute(): the image `name` (not a history) of the frame just recorded, with the
  // layout that frame left it in. Valid until the next frame is executed or resources are
  // reallocated. Throws bounce::Error for an unknown, culled or buffer resource.
  ResolvedImage resolvedImage(const std::string& name) const;

 private:
  friend class PassBuilder;
  friend class PassResources;

  enum class HistoryRole { None, Current, Previous };
  struct ResourceDecl {
    std::string name;
    ResourceKind kind = ResourceKind::Transient;
    bool isImage = false;
    ImageDesc image;
    BufferDesc buffer;
    HistoryRole role = HistoryRole::None;
    std::string group;  // the history's name for both sides of a history; else the name
    ImportedImage importedImage;
    ImportedBuffer importedBuffer;
  };
  struct ResourceUse {
    uint32_t resource = 0;
    Access access = Access::StorageRead;
    AccessInfo info;
    uint32_t binding = kNoBinding;  // the shader binding of a bound image
    // Reads of the same resource merged into this one (a buffer read as storage and as indirect
    // arguments): each adds its usage flags.
    std::vector<Access> mergedReads;
  };
  struct PassDecl {
    std::string name;
    QueueKind kind = QueueKind::Compute;
    std::vector<ResourceUse> uses;
    std::vector<std::pair<uint32_t, uint32_t>> placeholders;  // (resource, binding)
    bool sideEffects = false;
    RecordFn record;
    uint32_t runsAfter = kNoResource;  // debug-view copies: the pass shown; else unused
  };
  struct HistoryInfo {
    uint32_t parity = 0;  // which of the pair is `current` this frame
    bool valid = false;
  };
  struct DebugViewRequest {
    std::string name;
    uint32_t target = kNoResource;    // resource shown, this frame
    uint32_t readback = kNoResource;  // its readback buffer, this frame
    bool captured = false;
    DebugView view;  // metadata of the last capture (bytes stay in the readback buffer)
  };
  struct PhysicalResource {
    vk::Image image;
    vk::Buffer buffer;
    VkImageUsageFlags usage = 0;  // image or buffer usage it was created with
    vk::MemoryUse memory = vk::MemoryUse::DeviceOnly;
  };
  struct Resolved {
    ResolvedImage image;
    ResolvedBuffer buffer;
  };

  // declaration (frame_graph.cpp)
  uint32_t declareResource(ResourceDecl decl);
  void checkNewResourceName(const std::string& name) const;
  void checkNewPassName(const std::string& name) const;
  const ResourceDecl& resourceDecl(uint32_t index, const char* expected) const;
  std::string physicalKey(const ResourceDecl& resource) const;
  std::string validNames() const;

  // compiling (frame_graph_compile.cpp)
  void removeInternalDeclarations();
  void addDebugViewPasses();
  void addDebugViewPass(DebugViewRequest& request);
  uint32_t debugViewTarget(const std::string& name) const;
  BufferDesc readbackDesc(const ResourceDecl& target) const;
  std::vector<uint32_t> executionOrder() const;
  void validate(const std::vector<uint32_t>& order) const;
  std::vector<bool> findLivePasses(const std::vector<uint32_t>& order) const;
  ResourceState entryState(const ResourceDecl& resource) const;
  void deriveBarriers(const std::vector<uint32_t>& order, const std::vector<bool>& live);
  void collectUsage(const std::vector<bool>& livePasses);
  bool hostVisible(const ResourceDecl& resource) const;

  // GPU (frame_graph_gpu.cpp)
  bool matches(const PhysicalResource& physical, uint32_t resource) const;
  void create(PhysicalResource& physical, uint32_t resource, const std::string& key);
  void zeroNewResources(const std::vector<std::string>& keys);
  void resolveResources();
  void recordPass(VkCommandBuffer cmd, const PassPlan& pass, vk::GpuTimer* timer);
  void recordBarriers(VkCommandBuffer cmd, const std::vector<PlannedBarrier>& barriers);
  void recordDebugViewCopy(VkCommandBuffer cmd, const PassResources& resources,
                           DebugViewRequest& request);

  // this frame's declarations
  std::vector<ResourceDecl> resources_;
  std::vector<PassDecl> passes_;
  size_t declaredResources_ = 0;  // the rest are the graph's own (debug-view readbacks)
  size_t declaredPasses_ = 0;

  // compiled
  FramePlan plan_;
  bool compiled_ = false;
  std::vector<bool> liveResources_;
  std::vector<VkFlags> usage_;  // image or buffer usage per resource

  // across frames
  std::map<std::string, ResourceState> states_;  // by physical key
  std::map<std::string, uint64_t> importedHandles_;
  std::map<std::string, HistoryInfo> history_;
  std::vector<DebugViewRequest> debugViews_;
  uint64_t frameIndex_ = 0;

  // GPU
  vk::Context* context_ = nullptr;
  VkExtent2D resolution_{};
  std::map<std::string, PhysicalResource> physical_;
  std::vector<Resolved> resolved_;
  std::vector<BoundImage> boundImages_;  // the recording pass's, scratch reused every frame
  std::vector<VkImageMemoryBarrier2> imageBarriers_;  // scratch, reused every frame
  std::vector<VkBufferMemoryBarrier2> bufferBarriers_;
};

}  // namespace bounce::graph
