#include "scene_render/scene_report.h"

#include <variant>

namespace shadelab::scene_render {

std::string_view PassTiming::name() const {
  struct Name {
    std::string_view operator()(const SetupDetail&) const { return "setup"; }
    std::string_view operator()(const ShadowDetail&) const { return "shadow"; }
    std::string_view operator()(const ReflectionDetail&) const { return "reflection"; }
    std::string_view operator()(const MainDetail&) const { return "main"; }
    std::string_view operator()(const ViewDetail&) const { return "view"; }
    std::string_view operator()(const ReadbackDetail&) const { return "readback"; }
    std::string_view operator()(const FramingDetail&) const { return "framing"; }
  };
  return std::visit(Name{}, detail);
}

}  // namespace shadelab::scene_render
