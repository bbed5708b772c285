// Readable debug views of ReSTIR DI's resources (docs/di.md, "Debug views"). The frame graph
// shows a resource's raw texels; a reservoir (restir_di_io.h) keeps W and M as float bits in a
// uint image, and di.reservoir-info packs four quantities in one texel. HybridFrame maps:
//   di.candidate, di.reservoir, di.spatial   decoded: (light index or -1, M, W, 0)
//   di.light        di.reservoir-info's light as a colour per light (hashed), black for none
//   di.m            its M (grey: M over the image's largest M)
//   di.w            its W (grey: W over 4x its mean where positive, clipped at 1)
//   di.visibility   its final shadow ray: 1 visible, 0 occluded, 0.25 where none was traced
#pragma once
#include <string>
#include <vector>

#include "graph/frame_graph.h"
#include "tools/image_io.h"

namespace bounce {

// The derived views above (di.light, di.m, di.w, di.visibility).
std::vector<std::string> diDerivedViewNames();
bool isDiDerivedView(const std::string& name);
// The resource a derived view is computed from (di.reservoir-info).
inline constexpr const char* kDiInfoResource = "di.reservoir-info";
// `info` is di.reservoir-info's image (graph::debugViewImage).
ImageRGBA32F diDerivedView(const std::string& name, const ImageRGBA32F& info);

// Whether a captured view holds reservoirs (kDiReservoirFormat), and their decoding.
bool isDiReservoirView(const graph::DebugView& view);
ImageRGBA32F decodeDiReservoirView(const graph::DebugView& view);

}  // namespace bounce
