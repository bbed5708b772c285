// ReSTIR DI's world-space light grid (ReGIR: Boksansky et al. 2021, "Rendering many lights with
// grid-based reservoirs", Ray Tracing Gems II ch. 23; GI-1.0's light grid,
// research/gi10_lux_denoisers.md §1.5 and §2.3(b)): the candidate source of di-generate-candidates
// above DiSettings::lightGridThreshold local lights (src/di/di_light_grid.h, docs/di.md).
//
// A box of cellsX x cellsY x cellsZ cubic cells of cellSize, centred on the camera and snapped
// to whole cells (so a cell's box is the same from frame to frame while the camera stays in its
// cell), whose origin every pass derives from the frame's camera (diLightGridOrigin). Each frame
// di-light-grid fills every cell's slotsPerCell slots with one local light each, chosen by RIS
// from a pool of buildCandidates alias-table candidates (by power) that the cell's slots share,
// with the target diCellTarget: the
// light's unshadowed contribution bound over the cell's box (no surface, so no BRDF or cosine
// there). A slot holds (light, W): W is RIS's unbiased contribution weight of that light
// (1 / the slot's pdf of choosing it, estimated), DI_NO_LIGHT and 0 when no candidate reached
// the cell.
#ifndef BOUNCE_SHARED_DI_LIGHT_GRID_IO_H
#define BOUNCE_SHARED_DI_LIGHT_GRID_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Uploaded once (RestirDi's constructor); DiConstants::lightGrid points at it, 0 without a grid.
struct DiLightGrid {
  DeviceAddress slots;  // uvec2[cellsX * cellsY * cellsZ * slotsPerCell]: (light, W bits)
  uint cellsX;
  uint cellsY;
  uint cellsZ;
  float cellSize;        // world units
  uint slotsPerCell;     // reservoirs per cell
  uint buildCandidates;  // alias-table candidates per cell, a multiple of DI_LIGHT_GRID_GROUP_SIZE
  uint gridCandidates;   // of DiConstants::lightCandidates, how many come from the grid
  uint pad0;
};
BOUNCE_CHECK_SIZE(DiLightGrid, 40);

// Threads of di-light-grid's workgroup, one workgroup per cell: each draws an equal share of the
// cell's pool of candidates.
BOUNCE_CONST uint DI_LIGHT_GRID_GROUP_SIZE = 64u;

BOUNCE_END_SHARED
#endif
