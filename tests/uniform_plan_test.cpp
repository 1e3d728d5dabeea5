// render/uniform_plan.cpp: pure CPU, fed a program's reflection as GL reports it.
#include <gtest/gtest.h>

#include <GLES3/gl3.h>

#include "course/course_reader.h"
#include "render/uniform_plan.h"

using namespace shadelab;

namespace {

// What the built-in course's page sets every program.
const std::vector<render::ConstantUniform>& page() {
  static const auto uniforms = course::builtin_course().page().uniforms;
  return uniforms;
}

std::vector<float> course_value(const std::string& role) {
  const auto& v = course::builtin_course().uniform_with_role(*course::uniform_role_named(role))->value;
  return {v.begin(), v.end()};
}

gl::ActiveVariable active(const std::string& name, unsigned type, int array_size = 1) {
  return {name, gl::glsl_type(type), array_size, 0};
}

const render::UniformAssignment* assigned(const render::UniformPlan& plan, const std::string& name) {
  for (const auto& a : plan.constant)
    if (a.uniform->name == name) return &a;
  return nullptr;
}

bool warned(const render::UniformPlan& plan, const std::string& needle) {
  for (const auto& w : plan.warnings)
    if (w.find(needle) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(UniformPlanTest, TheCoursesValuesFeedWhatTheProgramDeclares) {
  const std::vector<gl::ActiveVariable> program = {active("uAmbientColor", GL_FLOAT_VEC4), active("uLightPosition", GL_FLOAT_VEC3),
                                                   active("uWorldToClipSpaceMatrix", GL_FLOAT_MAT4), active("uMeshToWorldMatrix", GL_FLOAT_MAT4)};
  auto plan = render::plan_uniforms(program, page(), {});
  ASSERT_TRUE(plan) << plan.error().message;
  const auto* ambient = assigned(*plan, "uAmbientColor");
  ASSERT_TRUE(ambient);
  EXPECT_EQ(ambient->values, course_value("ambient"));
  const auto* light = assigned(*plan, "uLightPosition");
  ASSERT_TRUE(light);
  EXPECT_EQ(light->values, course_value("lightPosition"));
  EXPECT_TRUE(plan->world_to_clip);
  EXPECT_TRUE(plan->mesh_to_world);
  EXPECT_FALSE(plan->mesh_to_world_rot);  // not declared: not fed
  EXPECT_TRUE(plan->warnings.empty());
}

TEST(UniformPlanTest, ARequestValueOverridesTheDefaultAndAnArrayMayBeNamedWithoutItsIndex) {
  const std::vector<gl::ActiveVariable> program = {active("uDiffuseColor", GL_FLOAT_VEC4), active("weights[0]", GL_FLOAT, 3)};
  auto plan = render::plan_uniforms(program, page(), {{"uDiffuseColor", {0.2, 0.6, 0.9, 1}}, {"weights", {1, 2, 3}}});
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_EQ(assigned(*plan, "uDiffuseColor")->values, (std::vector<float>{0.2f, 0.6f, 0.9f, 1.f}));
  EXPECT_EQ(assigned(*plan, "weights[0]")->values, (std::vector<float>{1.f, 2.f, 3.f}));
  EXPECT_EQ(plan->constant.size(), 2u) << "the default must not be fed on top of the request's value";
}

TEST(UniformPlanTest, AValueThatDoesNotFitTheTypeIsAnErrorNamingBoth) {
  const std::vector<gl::ActiveVariable> program = {active("uColor", GL_FLOAT_VEC4), active("uCount", GL_INT),
                                                   active("uFlag", GL_BOOL), active("uIndex", GL_UNSIGNED_INT),
                                                   active("uTexture", GL_SAMPLER_2D)};
  const auto error_of = [&](render::UniformSetting s) {
    auto plan = render::plan_uniforms(program, page(), {std::move(s)});
    EXPECT_FALSE(plan);
    return plan ? std::string() : plan.error().message;
  };
  EXPECT_NE(error_of({"uColor", {1, 2, 3}}).find("3 numbers were given, 4 are needed"), std::string::npos);
  EXPECT_NE(error_of({"uCount", {1.5}}).find("whole numbers"), std::string::npos);
  EXPECT_NE(error_of({"uFlag", {2}}).find("0 or 1"), std::string::npos);
  EXPECT_NE(error_of({"uIndex", {-1}}).find("non-negative"), std::string::npos);
  EXPECT_NE(error_of({"uTexture", {0}}).find("cannot be set"), std::string::npos);
  auto plan = render::plan_uniforms(program, page(), {{"uColor", {1}}});
  ASSERT_FALSE(plan);
  EXPECT_EQ(plan.error().code, ErrorCode::uniform_type_mismatch);
}

TEST(UniformPlanTest, WhatTheProgramDoesNotUseOrDeclaresDifferentlyIsAWarningNotAnError) {
  const std::vector<gl::ActiveVariable> program = {active("uAmbientColor", GL_FLOAT_VEC3), active("uMeshToWorldMatrix", GL_FLOAT_MAT3),
                                                   active("uWorldToClipSpaceMatrix", GL_FLOAT_MAT4)};
  auto plan = render::plan_uniforms(program, page(), {{"uNotThere", {1}}, {"uWorldToClipSpaceMatrix", std::vector<double>(16, 0.0)}});
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_TRUE(warned(*plan, "'uNotThere' is not used"));
  EXPECT_TRUE(warned(*plan, "'uAmbientColor' is declared vec3, but the homework page sets it as a vec4"));
  EXPECT_TRUE(warned(*plan, "'uMeshToWorldMatrix' is declared mat3"));
  EXPECT_FALSE(assigned(*plan, "uAmbientColor")) << "the browser leaves a mistyped uniform at zero";
  EXPECT_FALSE(plan->mesh_to_world);
  EXPECT_FALSE(plan->world_to_clip) << "a request's value is constant, not fed per frame";
  EXPECT_TRUE(assigned(*plan, "uWorldToClipSpaceMatrix"));
}
