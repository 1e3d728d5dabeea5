#pragma once
// What `shadelab grade` and `shadelab autograde` share: the grading flags, finding a submission's
// shader pair, and grading one pair through render workers, so that a submission that hangs or
// crashes is scored 0 with the reason.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "cli/environment.h"
#include "course/course.h"
#include "course/submission_files.h"
#include "grade/reference_store.h"
#include "road/submission.h"

namespace shadelab::cli {

// Unset facts (empty, nullopt) are the course's: its default checkpoint and mesh, its canvas and frames.
struct GradeFlags {
  std::string course;
  std::string cache_dir = grade::default_reference_folder();  // the reference store; empty: memory only
  std::string vert, frag, saved_frames, submissions, reference, mesh, out = "grades", output, heatmap;
  std::string format = "json", size;
  std::optional<int> frames;
  int workers = 0, concurrency = 0;
  std::string server, api_key, shard = "0/1";
  long retry_for_s = 300;
  std::optional<double> threshold, max_failing;  // unset: the course's tolerance
  double max_score = 1.0;
  bool spatial = false;
  int repair_candidates = road::RepairBudget{}.candidates;  // a failing grade's repair search (road/repair_search.h); 0: none
  int class_candidates = road::RepairBudget{}.class_candidates;  // a class batch's second search, beside its passing programs; 0: none
  // A TA's own `grade` shows the repaired line; what students receive shows what their course says.
  bool show_repaired_line = false;
  grade::HeatMap heatmaps = grade::HeatMap::never;  // a class batch writes none; a command that does says when
  // `course warm`: the grade makes every render a student's may read (grade::GradeSpec::warm),
  // with no repair search (its candidates are the student's own programs, never kept).
  bool warm_store = false;
  long timeout_ms = 10000;
  bool software = software_from_environment();
};

std::string read_text(const std::filesystem::path& p);

// A saved frame as a browser wrote it is ~0.1-1 MB at 512 x 512; a file far larger is not one.
inline constexpr std::uintmax_t kMaxFrameBytes = 32u << 20;

// The submission's shader pair for `checkpoint`: its files by the course's names for it
// (course/submission_files.h), else the only *_vert.js / *_frag.js pair in the folder.
std::optional<std::pair<std::filesystem::path, std::filesystem::path>> find_pair(const course::Course& course, const std::filesystem::path& dir,
                                                                                   const course::Checkpoint& checkpoint);

// One submission's grade, by the grading road (road/submission.h): whatever the submission
// causes (it does not compile, hangs, crashes the driver) is its grade, 0 with the reason; what it
// does not cause (the grader's own work failed, no worker could start, a bad flag) is an error.
// `classmates`: a class batch's passing programs, read beside the student's by a repair search.
using Graded = road::CodeGrade;
Expected<Graded> grade_one(worker::WorkerPool& pool, const course::Course& course, const GradeFlags& f, const std::filesystem::path& vert,
                           const std::filesystem::path& frag);
// The same for shaders already in memory.
Expected<Graded> grade_pair(worker::WorkerPool& pool, const course::Course& course, const GradeFlags& f, shader::ShaderFile vert,
                            shader::ShaderFile frag);
// A class batch's second search: the pair graded again with `classmates`, the class's passing
// programs, read beside it by the repair search; none where they offer nothing the first search
// did not try (road::second_search_has_candidates).
Expected<std::optional<Graded>> grade_beside_class(worker::WorkerPool& pool, const course::Course& course, const GradeFlags& f,
                                                   const std::filesystem::path& vert, const std::filesystem::path& frag,
                                                   std::vector<repair::PassingProgram> classmates);

// A deliverable's saved frames (`files`, relative to `root`) graded against `checkpoint`'s
// reference and, with `code` (vertex, fragment; relative to `root`), against what that code
// renders. A frame missing, unreadable or too large is the frames' grade, 0 with the file named.
using GradedFrames = road::FramesGrade;
Expected<GradedFrames> grade_saved_frames(worker::WorkerPool& pool, const course::Course& course, const GradeFlags& f,
                                          const course::Checkpoint& checkpoint, const std::filesystem::path& root,
                                          const course::SavedFrameFiles& files,
                                          const std::optional<std::pair<std::filesystem::path, std::filesystem::path>>& code);

// The same for frames already in memory (`code`: vertex, fragment).
Expected<GradedFrames> grade_frame_set(worker::WorkerPool& pool, const course::Course& course, const GradeFlags& f,
                                       const course::Checkpoint& checkpoint, std::vector<grade::SavedFrame> saved,
                                       const std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>>& code);

// Workers for `jobs` submissions: one per core at most, the cores shared among them.
worker::PoolConfig pool_config(const GradeFlags& f, int jobs);

}  // namespace shadelab::cli
