#include "di/di_settings.h"

#include <cmath>

#include "core/error.h"

namespace bounce {

std::optional<DiMode> diModeFromName(const std::string& name) {
  if (name == "off") return DiMode::Off;
  if (name == "uniform") return DiMode::Uniform;
  if (name == "restir") return DiMode::Restir;
  return std::nullopt;
}

const char* diModeNames() {
  return "restir, uniform, off";
}

std::optional<DiDenoiser> diDenoiserFromName(const std::string& name) {
  if (name == "none") return DiDenoiser::None;
  if (name == "svgf") return DiDenoiser::Svgf;
  if (name == "reblur") return DiDenoiser::Reblur;
  return std::nullopt;
}

const char* diDenoiserName(DiDenoiser denoiser) {
  switch (denoiser) {
    case DiDenoiser::None:
      return "none";
    case DiDenoiser::Svgf:
      return "svgf";
    case DiDenoiser::Reblur:
      return "reblur";
  }
  return "?";
}

std::optional<DiCandidateVisibility> diCandidateVisibilityFromName(const std::string& name) {
  if (name == "auto") return DiCandidateVisibility::Auto;
  if (name == "on") return DiCandidateVisibility::On;
  if (name == "off") return DiCandidateVisibility::Off;
  return std::nullopt;
}

const char* diDenoiserNames() {
  return "svgf, reblur, none";
}

void validate(const DiSettings& s) {
  if (s.lightCandidates < 1 || s.lightCandidates > 64)
    fail("DI light candidates {}: expected 1 to 64", s.lightCandidates);
  if (s.brdfCandidates > 1) fail("DI BRDF candidates {}: expected 0 or 1", s.brdfCandidates);
  if (!(s.brdfCandidateMaxRoughness >= 0.0f && s.brdfCandidateMaxRoughness <= 1.0f))
    fail("DI BRDF candidate max roughness {}: expected 0 to 1", s.brdfCandidateMaxRoughness);
  if (!(s.temporalMaxM >= 1.0f && s.temporalMaxM <= 1000.0f))
    fail("DI temporal M cap {}: expected 1 to 1000", s.temporalMaxM);
  if (!(s.depthTolerance > 0.0f) || !std::isfinite(s.depthTolerance))
    fail("DI depth tolerance {}: must be > 0", s.depthTolerance);
  if (!(s.normalTolerance >= -1.0f && s.normalTolerance <= 1.0f))
    fail("DI normal tolerance {}: expected a cosine in [-1, 1]", s.normalTolerance);
  if (s.spatialSamples > 8) fail("DI spatial samples {}: expected 0 to 8", s.spatialSamples);
  if (s.disocclusionSamples > 8)
    fail("DI disocclusion samples {}: expected 0 to 8", s.disocclusionSamples);
  if (!(s.disocclusionM >= 0.0f) || !std::isfinite(s.disocclusionM))
    fail("DI disocclusion M {}: must be >= 0", s.disocclusionM);
  if (!(s.spatialRadius >= 1.0f && s.spatialRadius <= 256.0f))
    fail("DI spatial radius {} pixels: expected 1 to 256", s.spatialRadius);
  for (uint32_t cells : {s.lightGridCellsX, s.lightGridCellsY, s.lightGridCellsZ})
    if (cells < 1 || cells > 128)
      fail("DI light grid: {} cells along an axis: expected 1 to 128", cells);
  if (!(s.lightGridCellSize >= 0.0f) || !std::isfinite(s.lightGridCellSize))
    fail("DI light grid cell size {}: must be >= 0 (0: automatic)", s.lightGridCellSize);
  if (s.lightGridSlots < 1 || s.lightGridSlots > 1024)
    fail("DI light grid slots {}: expected 1 to 1024", s.lightGridSlots);
  if (uint64_t(s.lightGridCellsX) * s.lightGridCellsY * s.lightGridCellsZ * s.lightGridSlots >
      (uint64_t(1) << 22))
    fail("DI light grid: {}x{}x{} cells of {} slots: at most 4,194,304 slots", s.lightGridCellsX,
         s.lightGridCellsY, s.lightGridCellsZ, s.lightGridSlots);
  if (s.lightGridBuildCandidates < 64 || s.lightGridBuildCandidates > 4096 ||
      s.lightGridBuildCandidates % 64 != 0)
    fail("DI light grid build candidates {}: expected a multiple of 64 from 64 to 4096",
         s.lightGridBuildCandidates);
  if (s.lightGridCandidates >= s.lightCandidates && s.lightCandidates > 1)
    fail(
        "DI light grid candidates {}: at most {} (one of the {} light candidates stays the alias "
        "table's)",
        s.lightGridCandidates, s.lightCandidates - 1, s.lightCandidates);
  if (s.finalVisibilityMaxAge > 64)
    fail("DI final visibility max age {}: expected 0 (always trace) to 64 frames",
         s.finalVisibilityMaxAge);
  if (s.unbiased && s.candidateVisibility != DiCandidateVisibility::On)
    fail(
        "DI unbiased configuration without candidate visibility: the ray-traced correction "
        "needs the candidates' shadow ray");
}

}  // namespace bounce
