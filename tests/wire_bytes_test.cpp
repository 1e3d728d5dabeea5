// The worker wire's bytes, pinned. Real jobs, built from the course as the road and the routes
// build them, and the answers a real worker gave to them were recorded once as fixtures
// (tests/wire/*.msg, each one message as worker/protocol.h lays it out). Today's build must encode
// each job to the same bytes, and read each answer and write it again to the same bytes. A change
// in how a struct's JSON is declared that renames, drops or retypes a key fails here; a round trip
// (reading back what this build wrote) cannot see that.
//
// Record again only for a change to the wire that is meant (SHADELAB_RECORD_WIRE=1 runs the jobs
// on a real worker and writes the fixtures), and say in the commit what changed and why.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/embedded_files.h"
#include "course/course.h"
#include "scene/scene_description.h"
#include "support/test_support.h"
#include "worker/course_job.h"
#include "worker/job.h"
#include "worker/pool.h"
#include "worker/protocol.h"
#include "worker/result.h"

using namespace shadelab;
namespace fs = std::filesystem;

namespace {

const fs::path kFixtures = fs::path(SHADELAB_SOURCE_DIR) / "tests" / "wire";

bool recording() { return std::getenv("SHADELAB_RECORD_WIRE") != nullptr; }

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string fixture(const std::string& name) {
  const fs::path path = kFixtures / (name + ".msg");
  EXPECT_TRUE(fs::exists(path)) << path << " is missing: record it with SHADELAB_RECORD_WIRE=1";
  return read_bytes(path);
}

// A real worker, only when recording.
worker::WorkerPool& recorder() {
  static worker::WorkerPool pool([] {
    worker::PoolConfig config;
    config.workers = 1;
    config.executable = SHADELAB_CLI;
    config.warm_up = worker::WarmUp::none;
    return config;
  }());
  return pool;
}

// The answer to `job`: a real worker's when recording (written as the fixture), else the fixture.
worker::Message answer_to(const std::string& name, const worker::Message& job) {
  if (!recording()) {
    auto decoded = worker::decode_message(fixture(name + ".answer"));
    EXPECT_TRUE(decoded.ok()) << name;
    return decoded ? *decoded : worker::Message{};
  }
  auto submitted = recorder().submit(job);
  EXPECT_TRUE(submitted.ok()) << name;
  worker::JobResult result = submitted->get();
  EXPECT_TRUE(result.answered) << name << ": " << result.error.message;
  write_bytes(kFixtures / (name + ".answer.msg"), worker::encode_message(result.answer));
  return result.answer;
}

// The job built today encodes to the recorded bytes, and the recorded bytes read as a job encode
// to themselves.
void expect_job_bytes(const std::string& name, const worker::Message& built, auto read_back) {
  const std::string bytes = worker::encode_message(built);
  if (recording()) write_bytes(kFixtures / (name + ".job.msg"), bytes);
  const std::string recorded = fixture(name + ".job");
  EXPECT_EQ(bytes, recorded) << name << ": the job's bytes changed";
  auto decoded = worker::decode_message(recorded);
  ASSERT_TRUE(decoded.ok()) << name;
  EXPECT_EQ(worker::encode_message(read_back(*decoded)), recorded) << name << ": the job read back writes other bytes";
}

void expect_job_bytes(const std::string& name, const worker::Message& built) {
  expect_job_bytes(name, built, [](const worker::Message& m) {
    auto job = worker::job_from_message(m);
    EXPECT_TRUE(job.ok()) << (job ? "" : job.error().message);
    if (job && job->kind == worker::JobKind::grade_frames) {
      auto payload = worker::frames_payload_from(m);
      EXPECT_TRUE(payload.ok());
      return worker::to_message(*job, *payload);
    }
    return worker::to_message(*job, m.payload);
  });
}

// The recorded answer read as `Result` (or as its error) writes its own bytes again: all but the
// worker's own report on its caches, which the worker adds to every answer (worker_main.cpp).
template <class Result>
void expect_answer_bytes(const std::string& name, const worker::Message& answer) {
  worker::Message answered = answer;
  answered.header.erase("event");
  answered.header.erase("caches");
  const std::string recorded = worker::encode_message(answered);
  auto read = worker::result_from<Result>(answer);
  const worker::Message again = read ? worker::answer(*read) : worker::answer(read.error());
  EXPECT_EQ(worker::encode_message(again), recorded) << name << ": the answer read back writes other bytes";
}

const course::Course& the_course() { return testkit::course(); }

// The course's job of `kind` on its default mesh, at a canvas small enough to keep as a fixture.
worker::Job small_job(worker::JobKind kind, const std::string& preset) {
  worker::Job job = worker::course_job(the_course(), kind);
  std::string payload;
  EXPECT_TRUE(worker::attach_course_mesh(the_course(), the_course().default_mesh, job, payload).ok());
  const course::Preset* p = the_course().preset(preset);
  job.request = the_course().render_request(p->vertex, p->fragment);
  job.request.width = job.request.height = 64;
  job.request.frames = 3;
  job.prefix = preset;
  return job;
}

worker::Job grade_job(const std::string& checkpoint, const grade::Mistake* as_student) {
  const course::Checkpoint& c = *the_course().checkpoint(checkpoint)->checkpoint;
  worker::Job job = small_job(worker::JobKind::grade, c.reference);
  job.grade = the_course().grade_spec(c, the_course().grade_options(c));
  if (as_student) {
    job.request.vertex = as_student->vertex;
    job.request.fragment = as_student->fragment;
  }
  return job;
}

scene::SceneDescription small_scene() {
  auto parsed = scene::parse_scene(nlohmann::json::parse(*embedded_file("assets/scenes/two_objects.json")));
  EXPECT_TRUE(parsed.ok());
  scene::SceneDescription s = *parsed;
  s.render.width = 64;
  s.render.height = 48;
  s.render.shadow_map_size = 256;
  return s;
}

}  // namespace

TEST(WireBytesTest, RenderJobsAndTheirAnswersKeepTheirBytes) {
  worker::Job grid = small_job(worker::JobKind::render, "specular");
  worker::Job json = grid;
  json.output = worker::Output::json;
  worker::Job zip = grid;
  zip.output = worker::Output::frames;
  zip.notice = the_course().frames_download_notice();
  zip.fit = scene::Bounds{{-1, 0, -1}, {1, 2, 1}};
  zip.request.msaa = 0;
  zip.request.sample_position = std::array<double, 2>{0.25, 0.75};
  for (const auto& [name, job] : {std::pair{"render_grid", grid}, {"render_json", json}, {"render_zip", zip}}) {
    const auto message = worker::to_message(job);
    expect_job_bytes(name, message);
    expect_answer_bytes<worker::RenderResult>(name, answer_to(name, message));
  }
}

TEST(WireBytesTest, CompileAndMeshJobsAndTheirAnswersKeepTheirBytes) {
  worker::Job compile = small_job(worker::JobKind::compile, "starter");
  worker::Job broken = compile;
  const auto at = broken.request.fragment.text.find("void main");
  ASSERT_NE(at, std::string::npos);
  broken.request.fragment.text.insert(at, "float broken() { return undeclared; }\n");
  for (const auto& [name, job] : {std::pair{"compile", compile}, {"compile_error", broken}}) {
    const auto message = worker::to_message(job);
    expect_job_bytes(name, message);
    expect_answer_bytes<worker::CompileResult>(name, answer_to(name, message));
  }
  worker::Job mesh;
  mesh.kind = worker::JobKind::mesh_check;
  mesh.mesh = "sha256-triangle";
  mesh.mesh_format = "obj";
  const auto message = worker::to_message(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_job_bytes("mesh_check", message);
  expect_answer_bytes<worker::MeshCheckResult>("mesh_check", answer_to("mesh_check", message));
}

TEST(WireBytesTest, GradeJobsAndTheirAnswersKeepTheirBytes) {
  const course::Checkpoint& diffuse = *the_course().checkpoint("diffuse")->checkpoint;
  ASSERT_FALSE(diffuse.mistakes.empty());
  worker::Job passing = grade_job("specular", nullptr);
  const grade::GradeSpec diffuse_spec = the_course().grade_spec(diffuse, the_course().grade_options(diffuse));
  worker::Job failing = grade_job("diffuse", &diffuse_spec.mistakes.front());
  failing.grade.heatmap = grade::HeatMap::always;
  failing.request.width = failing.request.height = 192;  // large enough for the formula to read
  failing.grade.reference_store = {"", {.url = "redis://cache:6380/1", .timeout = std::chrono::milliseconds(900),
                                        .retry_after = std::chrono::milliseconds(3000), .time_to_live = std::chrono::seconds(3600),
                                        .max_value_bytes = 1u << 20}};
  for (const auto& [name, job] : {std::pair{"grade_passing", passing}, {"grade_failing", failing}}) {
    const auto message = worker::to_message(job);
    expect_job_bytes(name, message);
    expect_answer_bytes<worker::GradeResult>(name, answer_to(name, message));
  }
}

TEST(WireBytesTest, ASavedFramesJobAndItsAnswerKeepTheirBytes) {
  worker::Job render = small_job(worker::JobKind::render, "specular");
  render.output = worker::Output::json;
  auto rendered = worker::result_from<worker::RenderResult>(answer_to("render_json", worker::to_message(render)));
  ASSERT_TRUE(rendered.ok());
  worker::FramesPayload payload;
  for (const auto& f : rendered->frames) payload.saved.push_back({f.name, f.bytes});
  const course::Checkpoint& c = *the_course().checkpoint("specular")->checkpoint;
  worker::Job frames = small_job(worker::JobKind::grade_frames, c.reference);
  frames.grade = the_course().frames_grade_spec(c, the_course().grade_options(c));
  const auto message = worker::to_message(frames, payload);
  expect_job_bytes("grade_frames", message);
  expect_answer_bytes<worker::FramesGradeResult>("grade_frames", answer_to("grade_frames", message));
}

TEST(WireBytesTest, SceneAndImageJobsAndTheirAnswersKeepTheirBytes) {
  const scene::SceneDescription scene = small_scene();
  const auto scene_message = worker::to_message(worker::SceneJob{scene, {}});
  expect_job_bytes("scene", scene_message, [](const worker::Message& m) {
    auto job = worker::scene_job_from_message(m);
    EXPECT_TRUE(job.ok());
    return worker::to_message(*job);
  });
  const auto scene_answer = answer_to("scene", scene_message);
  expect_answer_bytes<worker::SceneResult>("scene", scene_answer);

  auto drawn = worker::result_from<worker::SceneResult>(scene_answer);
  ASSERT_TRUE(drawn.ok());
  worker::ImagesJob images{{{"images/two_objects.png", scene, 0, drawn->png, ""}, {"images/camera_25.png", std::nullopt, 2, "", "not in the submission"}}};
  const auto images_message = worker::to_message(images);
  expect_job_bytes("check_images", images_message, [](const worker::Message& m) {
    auto job = worker::images_job_from_message(m);
    EXPECT_TRUE(job.ok());
    return worker::to_message(*job);
  });
  expect_answer_bytes<worker::ImagesResult>("check_images", answer_to("check_images", images_message));
}
