#include "support/golden.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "image/encode.h"
#include "support/files.h"
#include "support/test_support.h"

namespace shadelab::testkit {

namespace {
namespace fs = std::filesystem;

// Beside the test binary, or SHADELAB_GOLDEN_FAILURES (a packed build's binaries may be read-only).
fs::path failures_dir() {
  const char* chosen = std::getenv("SHADELAB_GOLDEN_FAILURES");
  return chosen && *chosen ? fs::path(chosen) : fs::canonical("/proc/self/exe").parent_path() / "golden_failures";
}

void write(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}
}  // namespace

GoldenResult compare_with_golden(const std::string& name, const image::Image& actual, const GoldenTolerance& tol) {
  const fs::path golden = source_dir() / "tests" / "golden" / (name + ".png");
  auto encoded = image::encode_png(actual);
  if (!encoded) return {false, encoded.error().format()};

  if (const char* approve = std::getenv("SHADELAB_APPROVE_GOLDENS"); approve && std::string(approve) == "1") {
    write(golden, *encoded);
    return {true, "approved " + golden.string()};
  }
  std::ifstream in(golden, std::ios::binary);
  if (!in) return {false, "no golden " + golden.string() + " (run tools/approve_goldens.sh to create it)"};
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  const image::Image expected = decode(bytes);
  if (expected.width != actual.width || expected.height != actual.height)
    return {false, "size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) + " != golden " +
                       std::to_string(expected.width) + "x" + std::to_string(expected.height)};

  image::Image diff = image::Image::blank(actual.width, actual.height, image::PixelType::u8);
  size_t failing = 0;
  int worst = 0;
  for (size_t i = 0; i < actual.bytes.size(); i += 4) {
    int pixel_worst = 0;
    for (size_t c = 0; c < 4; ++c)
      pixel_worst = std::max(pixel_worst, std::abs(int(actual.bytes[i + c]) - int(expected.bytes[i + c])));
    worst = std::max(worst, pixel_worst);
    if (pixel_worst > tol.per_channel) ++failing;
    // Diff image: red where beyond tolerance, grey for smaller differences.
    const auto v = static_cast<std::uint8_t>(std::min(255, pixel_worst * 16));
    diff.bytes[i] = pixel_worst > tol.per_channel ? 255 : v;
    diff.bytes[i + 1] = pixel_worst > tol.per_channel ? 0 : v;
    diff.bytes[i + 2] = pixel_worst > tol.per_channel ? 0 : v;
    diff.bytes[i + 3] = 255;
  }
  const double fraction = static_cast<double>(failing) / static_cast<double>(actual.bytes.size() / 4);
  const std::string summary = std::to_string(failing) + " pixels (" + std::to_string(fraction * 100) +
                              "%) differ by more than " + std::to_string(tol.per_channel) + "/255; worst " +
                              std::to_string(worst) + "/255";
  if (fraction <= tol.max_failing_fraction) return {true, summary};
  write(failures_dir() / (name + "_actual.png"), *encoded);
  write(failures_dir() / (name + "_diff.png"), *image::encode_png(diff));
  return {false, summary + "; actual and diff written to " + failures_dir().string()};
}

}  // namespace shadelab::testkit
