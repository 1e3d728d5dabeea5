#pragma once
// The options the commands share, set up once here.
// `--course FILE` on every command that renders or grades: the course profile whose facts
// (canvas, frames, meshes, references, checkpoints) the command uses; the built-in one
// (courses/cs148-summer2022.json) when it is not given. Flags given explicitly (--size, --frames,
// ...) override the profile's values for that run only.
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "core/expected.h"
#include "course/course.h"
#include "scene/mesh.h"

namespace shadelab::cli {

void add_course_option(CLI::App* command, std::string& path);
// --software: Mesa's software renderer whatever the machine has (also SHADELAB_SOFTWARE=1).
void add_software_option(CLI::App* command, bool& software);
// --cache-dir on a grading command: where reference renders are kept across runs.
void add_cache_option(CLI::App* command, std::string& folder);
// What every command that grades takes: --course, --cache-dir and --software.
void add_grader_options(CLI::App* command, std::string& course, std::string& cache_dir, bool& software);
// --vert and --frag: a student's two shaders, each GLSL or the homework's JS module.
void add_shader_options(CLI::App* command, std::string& vert, std::string& frag);
// The course at `path`, or the built-in one for an empty path; shared, never copied per job.
Expected<std::shared_ptr<const course::Course>> load_course(const std::string& path);

// "WIDTHxHEIGHT" into the two numbers; invalid_argument naming the flag otherwise.
Status parse_size(const std::string& text, const std::string& flag, int& width, int& height);

// A --mesh argument: one of the course's meshes by name, else a mesh file; fitted into the
// course's framing when `fit` is set.
Expected<scene::Mesh> load_mesh_argument(const course::Course& course, const std::string& mesh, bool fit);

}  // namespace shadelab::cli
