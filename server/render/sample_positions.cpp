#include "render/sample_positions.h"

namespace shadelab::render {

namespace {

constexpr std::array<double, 2> kTwo[] = {{0.75, 0.75}, {0.25, 0.25}};
constexpr std::array<double, 2> kFour[] = {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};

}  // namespace

std::span<const std::array<double, 2>> standard_sample_positions(int samples) {
  switch (samples) {
    case 2: return kTwo;
    case 4: return kFour;
    default: return {};
  }
}

}  // namespace shadelab::render
