// Settings of Lux's ReSTIR indirect (`--gi lux`, seed 002; src/gi/lux/lux_gi.h).
#pragma once
#include <cstdint>

namespace bounce {

// What Lux adds to the ReSTIR GI stages it shares with Evolve (whose RestirGiSettings of the
// preset give the temporal, spatial and resolve settings; docs/gi/lux.md).
struct LuxSettings {
  // Cosine-distributed candidates per GI pixel and frame, resampled against the probe field
  // (lux-candidates; gi10_lux_denoisers.md §2.3(c): 2-4). Each costs an SH evaluation, no ray:
  // the one ray per pixel follows the chosen candidate. 1 = plain cosine sampling. 1 to 64.
  uint32_t candidates = 4;
  // p_hat's floor as a fraction of the probe's mean radiance (lux-candidates): keeps every
  // direction possible where the L1 probe says "dark" (ringing, lag) at the cost of some of the
  // variance reduction. 0 would be biased wherever the probe is wrong. (0, 10].
  float targetFloor = 0.1f;
  // Largest reconnection Jacobian the temporal and spatial reuse accept (replaces
  // RestirGiSettings::maxJacobian, Evolve's 10). Shifts with a larger Jacobian (a neighbour's
  // sample seen from much nearer: corners, contact) become rare, bright outliers; on cornell the
  // resolved estimate's variance falls 2.7x from 10 to 2 (docs/gi/lux.md). At least 1.
  float maxJacobian = 2.0f;
  // RestirGiSettings::canonicalResolve for Lux (its temporal pass always normalises by 1/Z).
  // Off: gi-restir-resolve averages the reservoirs whose shift to the pixel is accepted, so the
  // shifts the cap of 2 refuses cost no energy, but those it would accept with a larger
  // Jacobian are missing: the white furnace 4.6 % dark. On: unbiased over the refused shifts
  // (the furnace within 0.5 %), but the home reservoir then carries most of the weight and the
  // seed's 4x variance gate fails (2.6x on cornell; docs/gi/lux.md, "Measurements").
  bool unbiasedReuse = false;
  // SVGF (denoise/svgf.h, Falcor's settings) on the resolved GI (Lux's "Spatial"/"Hybrid"
  // denoisers are SVGF in §2.3(d)); off: the resolved estimate as it is.
  bool svgf = true;
  // Test support: lux-probe-integral runs with this many directions per GI pixel (0: not
  // declared), uniformly over the hemisphere (integralUniform) or cosine-distributed.
  uint32_t integralSamples = 0;
  bool integralUniform = false;
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const LuxSettings& settings);

}  // namespace bounce
