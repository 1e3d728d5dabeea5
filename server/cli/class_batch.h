#pragma once
// A class graded as a batch, however each submission is graded (by this process's render
// workers, or by a ShadeLab server): one folder per student, K at a time, a progress bar, and
// a journal that makes the batch resumable and splittable.
//
// | file in --out                         | what                                                   |
// |---------------------------------------|--------------------------------------------------------|
// | <student>/results.json                | Gradescope's results.json for that student             |
// | graded.jsonl (graded-shard-I-of-N.jsonl) | one line per finished student, appended as each ends |
// | summary.csv                           | every student found in the journals, sorted; `flags`: |
// |                                       | what the TA should look at (grade/provenance.h)       |
//
// A student with a line in any journal is not graded again, so the same command run again (or a
// job array's task rerun) carries on where it stopped.
//
// A second pass, where the batch can run one: a failing student for whom the repair search found
// no repair is graded again with the programs of the shard's passing students beside the course's
// reference (road/repair_search.h, repair/classmate_edits.h); their line is appended again, saying
// so, and their results.json rewritten. It runs once a student, resumed like the first.
//
// `--shard I/N` takes the students whose name hashes to I modulo N: stable when students are
// added, so shards never overlap.
#include <filesystem>
#include <functional>
#include <string>

#include "core/expected.h"
#include "grade/report.h"

namespace shadelab::cli {

struct Shard {
  int index = 0, count = 1;  // 0 <= index < count
};
// "I/N", 0 <= I < N.
Expected<Shard> parse_shard(const std::string& text);
bool in_shard(const std::string& student, const Shard& shard);

struct Student {
  std::string name;
  std::filesystem::path dir;
};

struct StudentGrade {
  grade::Report report;
  double seconds = 0;
  // The student's saved frames of the deliverable by their pixels (grade::fingerprint); empty when
  // they handed in none. Students who share one are flagged in the summary.
  std::string frames_fingerprint;
  // A second search with nothing to try (the class offers no edit the first did not): the student's
  // first grade stands, and is not graded again.
  bool first_grade_stands = false;
};

// Grades one student. An Error stops the batch (a wrong API key, a server gone for minutes):
// the student is not recorded, and the next run grades them.
using GradeStudent = std::function<Expected<StudentGrade>(const Student&)>;

// The second pass's grader, given the class's passing students (once, in name order).
using GradeWithClass = std::function<GradeStudent(const std::vector<Student>& passing)>;

struct BatchOptions {
  std::filesystem::path submissions, out;
  int concurrency = 1;
  Shard shard;
  std::string deliverable;  // the checkpoint graded, as the summary's flags name it
};

// Exit status: 0 when every student of the shard is graded, 1 when the batch stopped on an error.
// `with_class`: the second pass's grader; empty where the batch has none (a server grades each
// student alone).
int run_class_batch(const BatchOptions& options, const GradeStudent& grade_student, const GradeWithClass& with_class = {});

}  // namespace shadelab::cli
