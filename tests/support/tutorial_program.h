#pragma once
// The specular checkpoint written as a tutorial writes it (`lightDir`, `reflectDir`, `spec`, where
// the course's reference writes L, R and its exponent's constant): right, but for its names and
// its order, for the tests of what a class's passing programs offer (repair/classmate_edits.h).
#include <string>

namespace shadelab::testkit {

// The tutorial's fragment `main`, its closing brace included.
inline constexpr const char* kTutorialSpecularMain =
    "void main(void) {\n"
    "    vec3 norm = normalize(vNormal);\n"
    "    vec3 lightDir = normalize(uLightPosition - vPosition);\n"
    "    float diff = max(dot(norm, lightDir), 0.0);\n"
    "    vec4 color = uAmbientColor + diff * uDiffuseColor * uLightColor;\n"
    "    if (diff > 0.0) {\n"
    "        vec3 viewDir = normalize(-vPosition);\n"
    "        vec3 reflectDir = reflect(-lightDir, norm);\n"
    "        float spec = pow(max(dot(viewDir, reflectDir), 0.0), 6.0);\n"
    "        color += spec * uSpecularColor * uLightColor;\n"
    "    }\n"
    "    fragColor = color;\n"
    "}";

// The reference's fragment stage (its GLSL, or the course's JS module of it) with the tutorial's
// `main` in place of its own: the declarations, and whatever follows the last brace, kept.
inline std::string with_tutorial_main(const std::string& reference) {
  return reference.substr(0, reference.find("void main(void) {")) + kTutorialSpecularMain + reference.substr(reference.rfind('}') + 1);
}

}  // namespace shadelab::testkit
