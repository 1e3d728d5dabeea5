#include "image/view_transform.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <OpenColorIO/OpenColorIO.h>

namespace shadelab::image {

namespace {

namespace OCIO = OCIO_NAMESPACE;

// OCIO's processor for one conversion, as a CPU processor on packed float RGB (OCIO's default
// optimisation: the same one OpenImageIO's ColorProcessor used, so the tables are unchanged).
Expected<OCIO::ConstCPUProcessorRcPtr> processor(const std::string& config_path, const char* from, const char* to) {
  if (config_path.empty() || !std::filesystem::exists(config_path))
    return make_error(ErrorCode::view_transform_unavailable,
                      "the Filmic view transform needs Blender's OCIO config (Debian package blender-data, or "
                      "SHADELAB_OCIO_CONFIG); use viewTransform \"standard\" without it");
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(config_path.c_str());
  } catch (const std::exception& e) {
    return make_error(ErrorCode::view_transform_unavailable, "cannot read the OCIO config " + config_path + ": " + e.what());
  }
  try {
    return config->getProcessor(from, to)->getDefaultCPUProcessor();
  } catch (const std::exception& e) {
    return make_error(ErrorCode::view_transform_unavailable,
                      std::string("the OCIO config ") + config_path + " has no transform " + from + " -> " + to + ": " + e.what());
  }
}

// RGB triples in place, as one row. OCIO reports trouble by throwing; here it becomes an Error.
Status run_processor(const OCIO::CPUProcessor& p, std::vector<float>& rgb) {
  const long count = static_cast<long>(rgb.size() / 3);
  try {
    OCIO::PackedImageDesc row(rgb.data(), count, 1, 3);
    p.apply(row);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::view_transform_unavailable, std::string("OCIO failed: ") + e.what());
  }
  return Ok{};
}

}  // namespace

std::string blender_ocio_config_path() {
  if (const char* env = std::getenv("SHADELAB_OCIO_CONFIG"); env && *env) return env;
  const std::filesystem::path debian = "/usr/share/blender/datafiles/colormanagement/config.ocio";
  if (std::filesystem::exists(debian)) return debian.string();
  // Blender's own tarballs keep datafiles under a version directory.
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/usr/share/blender", ec)) {
    const auto candidate = entry.path() / "datafiles/colormanagement/config.ocio";
    if (std::filesystem::exists(candidate)) return candidate.string();
  }
  return "";
}

Expected<FilmicTables> bake_filmic(const std::string& config_path) {
  auto to_log = processor(config_path, "Linear", "Filmic Log");
  if (!to_log) return to_log.take_error();
  auto to_display = processor(config_path, "Filmic Log", "Filmic sRGB");
  if (!to_display) return to_display.take_error();

  FilmicTables t;
  t.config_path = config_path;
  constexpr int n = FilmicTables::kCubeSize;
  t.cube.resize(size_t{n} * n * n * 3);
  const auto linear = [](int i) {
    const double u = static_cast<double>(i) / (n - 1);
    return static_cast<float>(std::exp2(FilmicTables::kLog2Min + u * (FilmicTables::kLog2Max - FilmicTables::kLog2Min)));
  };
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        float* px = &t.cube[((size_t(b) * n + g) * n + r) * 3];
        px[0] = linear(r), px[1] = linear(g), px[2] = linear(b);
      }
  if (auto s = run_processor(**to_log, t.cube); !s) return s.take_error();

  constexpr int m = FilmicTables::kCurveSize;
  t.curve.resize(size_t{m} * 3);
  for (int i = 0; i < m; ++i)
    for (int c = 0; c < 3; ++c) t.curve[size_t(i) * 3 + c] = static_cast<float>(i) / (m - 1);
  if (auto s = run_processor(**to_display, t.curve); !s) return s.take_error();
  return t;
}

Status apply_filmic_reference(const std::string& config_path, std::vector<float>& rgb) {
  auto p = processor(config_path, "Linear", "Filmic sRGB");
  if (!p) return p.take_error();
  return run_processor(**p, rgb);
}

}  // namespace shadelab::image
