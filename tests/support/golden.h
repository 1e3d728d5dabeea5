#pragma once
// Golden-image comparison, as filament's backend tests do it: expected PNGs in tests/golden/, a
// per-channel tolerance, and on failure the actual and a diff image written next to the test
// binary. SHADELAB_APPROVE_GOLDENS=1 (tools/approve_goldens.sh) writes the actual images into
// tests/golden/ instead: re-approval is a deliberate act, never a side effect of a failing run.
#include <string>

#include "image/image.h"

namespace shadelab::testkit {

struct GoldenTolerance {
  int per_channel = 3;                // |actual - expected| allowed in any channel, in 1/255
  double max_failing_fraction = 0.0005;  // share of pixels allowed beyond that (edge rasterisation)
};

struct GoldenResult {
  bool passed = false;
  std::string message;
};

GoldenResult compare_with_golden(const std::string& name, const image::Image& actual, const GoldenTolerance& tol = {});

}  // namespace shadelab::testkit
