// Turns a debug view's texels into an image the tools can write (PNG/EXR): one channel shows as
// grey, two as red/green; integer formats show their values as numbers. Layer 0 only.
#pragma once
#include "graph/frame_graph.h"
#include "tools/image_io.h"

namespace bounce::graph {

// Throws bounce::Error for buffers and for formats it does not know.
ImageRGBA32F debugViewImage(const DebugView& view);

}  // namespace bounce::graph
