// How a pass touches a resource, and what that means to Vulkan. One table (access.cpp) maps each
// access to the pipeline stages, memory-access bits and image layout that the frame graph derives
// its barriers from, so no pass ever writes a barrier by hand.
#pragma once
#include <vulkan/vulkan.h>

namespace bounce::graph {

// The pipeline a pass runs on. Shader accesses take their stages from it (a sampled read in a
// compute pass happens in COMPUTE_SHADER, in a graphics pass in VERTEX/FRAGMENT_SHADER).
enum class QueueKind { Compute, Graphics };

enum class Access {
  SampledRead,           // texelFetch/texture on a sampled image
  StorageRead,           // imageLoad, buffer loads (buffer_reference pointers included)
  StorageWrite,          // imageStore, buffer stores; the previous contents are not read
  StorageReadWrite,      // read-modify-write, atomics
  ColorAttachmentWrite,  // render target of a graphics pass (a LOAD op also reads it)
  DepthAttachmentRead,   // depth test without depth writes
  DepthAttachmentWrite,  // depth test and depth writes
  TransferSrc,           // copy/blit source
  TransferDst,           // copy/blit/clear/fill destination
  IndirectRead,          // indirect dispatch/draw arguments (buffers only)
  HostRead,              // the host reads it once the submission has completed (buffers only)
};

struct AccessInfo {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
  bool writes = false;                               // changes the contents
  bool keepsContents = true;  // false: a pure overwrite, earlier contents are dead (culling)
  bool onImages = false;
  bool onBuffers = false;
};

AccessInfo accessInfo(Access access, QueueKind kind);
const char* accessName(Access access);
const char* queueKindName(QueueKind kind);

// The write bits of an access mask: only writes need to be made available by a barrier.
VkAccessFlags2 writeAccessBits(VkAccessFlags2 access);

// Image and buffer usage flags an access needs.
VkImageUsageFlags imageUsageFor(Access access);
VkBufferUsageFlags bufferUsageFor(Access access);

}  // namespace bounce::graph
