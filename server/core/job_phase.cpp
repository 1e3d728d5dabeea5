#include "core/job_phase.h"

#include "core/enum_names.h"

namespace shadelab {

namespace {

constexpr EnumName<JobPhase> kPhases[] = {{JobPhase::compile, "compile"}, {JobPhase::render, "render"}, {JobPhase::grader, "grader"}};
constexpr EnumName<JobPhase> kDoing[] = {
    {JobPhase::compile, "compiling"}, {JobPhase::render, "rendering"}, {JobPhase::grader, "rendering the grader's references"}};

}  // namespace

std::string_view to_string(JobPhase phase) { return name_in(kPhases, phase); }
std::optional<JobPhase> job_phase_named(std::string_view name) { return value_in(kPhases, name); }
std::string_view doing(JobPhase phase) { return name_in(kDoing, phase); }

}  // namespace shadelab
