// Writes wire_message's seeds: real jobs and answers as the service encodes them (a maintainer's
// tool, run after make_seeds.py: `build/tests/fuzz/fuzz_wire_seeds tests/fuzz/corpus/wire_message`).
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/embedded_files.h"
#include "course/course_reader.h"
#include "http/api_request.h"
#include "worker/job.h"
#include "worker/result.h"

using namespace shadelab;

namespace {
void write(const std::filesystem::path& dir, const std::string& name, const worker::Message& m) {
  std::ofstream(dir / name, std::ios::binary) << worker::encode_message(m);
}

worker::Job job_for(const std::string& body, worker::JobKind kind) {
  auto raw = http::from_json_body(body);
  auto parsed = http::parse_job(*raw, kind, http::Limits{}, course::builtin_course());
  if (!parsed) {
    std::fprintf(stderr, "%s\n", parsed.error().message.c_str());
    std::exit(1);
  }
  return parsed->job;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  write(dir, "job_render", worker::to_message(job_for(R"({"preset":"specular","frames":2,"width":32,"height":24})", worker::JobKind::render)));
  write(dir, "job_compile", worker::to_message(job_for(R"({"preset":"normals","uniforms":{"uShininess":8}})", worker::JobKind::compile)));
  write(dir, "job_render_mesh",
        worker::to_message(job_for(R"({"preset":"diffuse","mesh":"m0123456789abcdef","output":"json"})", worker::JobKind::render),
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  const auto scene_text = embedded_file("assets/scenes/two_objects.json");
  auto scene = scene::parse_scene(nlohmann::json::parse(*scene_text));
  write(dir, "job_scene", worker::to_message(worker::SceneJob{*scene, {{"tri", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}}}));
  worker::CompileResult compiled{{"a warning"}, {Diagnostic{"fragment", "f.js", 3, 5, "warning", "unused"}}, {{"aPosition", "vec3", 1}}, {{"uColor", "vec4", 1}}, 6.5};
  write(dir, "answer_compile", worker::answer(compiled));
  worker::RenderResult rendered;
  rendered.samples = 4;
  rendered.constant_frames = {{1, {0, 0, 0, 255}}};
  rendered.content_type = "image/png";
  rendered.body = "\x89PNG\r\n\x1a\n";
  rendered.frames = {{"hw2_render_0.png", "\x89PNG"}};
  write(dir, "answer_render", worker::answer(rendered));
  write(dir, "answer_mesh_check", worker::answer(worker::MeshCheckResult{12, true, {0, 0, 0}, {1, 2, 3}}));
  write(dir, "answer_scene", worker::answer(worker::SceneResult{{}, 3.5, "\x89PNG"}));
  write(dir, "answer_grade", worker::answer(worker::GradeResult{{}, "\x89PNG"}));
  write(dir, "answer_error", worker::answer(make_error(ErrorCode::compile_failed, "does not compile")));
  return 0;
}
