#include "cli/class_batch.h"
#include "cli/file_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "core/csv.h"
#include "core/hash.h"
#include "grade/provenance.h"
#include "road/submission.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One finished student, as the journal and the summary hold it.
struct Entry {
  std::string student;
  double score = 0, max_score = 0;
  bool pass = false;
  std::string diagnosis, message;
  std::string frames;              // the saved frames' fingerprint; empty: none handed in
  std::vector<std::string> flags;  // the grade's flags, in words
  std::string explanation;         // a failing grade's mistake, in a few words (grade::mistake_label); "" for none
  int renders = 0;                 // drawn at the grade's frames (road::full_renders)
  int screened = 0;                // repair candidates screened on a small canvas
  bool unrepaired = false;         // a repair search ran and confirmed none
  bool with_class = false;         // graded again beside the class's passing programs (the second pass)
};

json to_json(const Entry& e) {
  return {{"student", e.student}, {"score", e.score}, {"maxScore", e.max_score}, {"pass", e.pass},
          {"diagnosis", e.diagnosis}, {"message", e.message}, {"frames", e.frames}, {"flags", e.flags}, {"explanation", e.explanation},
          {"renders", e.renders}, {"screened", e.screened}, {"unrepaired", e.unrepaired}, {"withClass", e.with_class}};
}

std::optional<Entry> entry_from(const std::string& line) {
  const json j = json::parse(line, nullptr, false);
  if (!j.is_object() || !j.contains("student") || !j["student"].is_string()) return std::nullopt;  // a line cut short by a kill
  Entry e{j["student"], j.value("score", 0.0), j.value("maxScore", 0.0), j.value("pass", false), j.value("diagnosis", ""),
          j.value("message", ""), j.value("frames", ""), {}, j.value("explanation", ""), j.value("renders", 0), j.value("screened", 0),
          j.value("unrepaired", false), j.value("withClass", false)};
  for (const auto& f : j.value("flags", json::array()))
    if (f.is_string()) e.flags.push_back(f);
  return e;
}

Entry entry_of(const std::string& student, const StudentGrade& g) {
  const grade::Report& r = g.report;
  Entry e{student, r.score, r.max_score, r.pass, r.diagnosis, r.messages.empty() ? "" : r.messages[0], g.frames_fingerprint, {},
          grade::mistake_label(r), road::full_renders(r), r.repair_search ? r.repair_search->candidates : 0,
          r.repair_search && !r.repair_search->found};
  for (const auto& f : r.flags) e.flags.push_back(f.message);
  return e;
}

// Students whose saved frames are another's too, pixel for pixel, each flagged naming the others.
void flag_shared_frames(std::map<std::string, Entry>& entries, const std::string& deliverable) {
  std::map<std::string, std::vector<std::string>> by_frames;
  for (const auto& [who, e] : entries)
    if (!e.frames.empty()) by_frames[e.frames].push_back(who);
  for (const auto& [frames, students] : by_frames) {
    if (students.size() < 2) continue;
    for (const auto& who : students) {
      std::vector<std::string> others;
      for (const auto& other : students)
        if (other != who) others.push_back(other);
      entries[who].flags.push_back(grade::same_frames_flag(deliverable, others).message);
    }
  }
}

std::string journal_name(const Shard& s) {
  if (s.count == 1) return "graded.jsonl";
  return "graded-shard-" + std::to_string(s.index) + "-of-" + std::to_string(s.count) + ".jsonl";
}

// Every student any journal in `out` records (this shard's and, in a shared folder, the others').
std::map<std::string, Entry> read_journals(const fs::path& out) {
  std::map<std::string, Entry> entries;
  if (!fs::is_directory(out)) return entries;
  for (const auto& f : fs::directory_iterator(out)) {
    const std::string name = f.path().filename().string();
    if (!name.starts_with("graded") || !name.ends_with(".jsonl")) continue;
    std::ifstream in(f.path());
    for (std::string line; std::getline(in, line);)
      if (auto e = entry_from(line)) entries[e->student] = std::move(*e);
  }
  return entries;
}

// Each student's results.json in a folder of its own under students/, so no student's folder name
// (summary.csv, graded.jsonl) can be one of the batch's own files.
fs::path student_results(const fs::path& out, const std::string& name) { return out / "students" / name / "results.json"; }

// Appends whole lines with one write each (O_APPEND), so a kill leaves at most one cut line,
// which the reader skips; a cut line is ended first so the next one starts clean.
class Journal {
 public:
  explicit Journal(const fs::path& path) : fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644)) {
    if (fd_ >= 0 && fs::file_size(path) > 0) {
      std::ifstream in(path, std::ios::binary);
      in.seekg(-1, std::ios::end);
      if (in.get() != '\n') append_raw("\n");
    }
  }
  ~Journal() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool ok() const { return fd_ >= 0; }
  void append(const Entry& e) { append_raw(to_json(e).dump() + "\n"); }

 private:
  void append_raw(const std::string& text) {
    std::lock_guard lock(mutex_);
    if (::write(fd_, text.data(), text.size()) != static_cast<ssize_t>(text.size())) std::cerr << "\nwarning: the journal write failed\n";
  }
  int fd_;
  std::mutex mutex_;
};


// A cell of the TA's CSV: a student's name made printable first (a CR in a folder name must not
// start a row of its own), then quoted and guarded against formulas (core/csv.h).
// ShadeLab's own messages keep one line a row, their line ends read as spaces.
std::string csv(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return csv_cell(printable(s));
}

std::string joined_flags(const std::vector<std::string>& flags) {
  std::string out;
  for (const auto& f : flags) out += (out.empty() ? "" : " | ") + f;
  return out;
}

Status write_summary(const fs::path& out, const std::map<std::string, Entry>& entries) {
  std::string summary = "student,score,max_score,pass,diagnosis,message,flags,explanation\n";
  for (const auto& [who, e] : entries)
    summary += csv(who) + "," + std::to_string(e.score) + "," + std::to_string(e.max_score) + "," + (e.pass ? "true" : "false") + "," +
               csv(e.diagnosis) + "," + csv(e.message) + "," + csv(joined_flags(e.flags)) + "," + csv(e.explanation) + "\n";
  return write_file(out / "summary.csv", summary);
}

// The failing students counted by what the formula says of them, most first (then by name).
std::vector<std::pair<std::string, std::vector<std::string>>> by_explanation(const std::map<std::string, Entry>& entries) {
  std::map<std::string, std::vector<std::string>> groups;
  for (const auto& [who, e] : entries)
    if (!e.explanation.empty()) groups[e.explanation].push_back(who);
  std::vector<std::pair<std::string, std::vector<std::string>>> out(groups.begin(), groups.end());
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });
  return out;
}

Status write_explanations(const fs::path& out, const std::map<std::string, Entry>& entries) {
  std::string text = "explanation,students,who\n";
  for (const auto& [label, who] : by_explanation(entries)) {
    std::string names;
    for (const auto& w : who) names += (names.empty() ? "" : " ") + w;
    text += csv(label) + "," + std::to_string(who.size()) + "," + csv(names) + "\n";
  }
  return write_file(out / "explanations.csv", text);
}

// What the class cost, counted rather than timed: the same on a busy or an idle machine.
void say_cost(const std::vector<Student>& students, const std::map<std::string, Entry>& entries) {
  int renders = 0, screened = 0;
  for (const auto& s : students)
    if (const auto e = entries.find(s.name); e != entries.end()) renders += e->second.renders, screened += e->second.screened;
  char per_student[32];
  std::snprintf(per_student, sizeof per_student, "%.2f", renders / static_cast<double>(std::max<size_t>(students.size(), 1)));
  std::cerr << "the grader drew " << renders << " renders at the grade's frames (" << per_student << " a student) and screened " << screened
            << " repair candidates on a small canvas\n";
}

// A student's folder is a folder of the submissions, not a link to somewhere else (another
// student's hand-in, the references): a link is refused by its name.
std::vector<Student> students_of(const BatchOptions& o) {
  std::vector<Student> students;
  for (const auto& e : fs::directory_iterator(o.submissions)) {
    const std::string name = e.path().filename().string();
    if (!in_shard(name, o.shard)) continue;
    if (e.is_symlink()) {
      std::cerr << "refused: " << printable(name) << " is a symbolic link, not a student's folder\n";
      continue;
    }
    if (e.is_directory()) students.push_back({name, e.path()});
  }
  std::sort(students.begin(), students.end(), [](const Student& a, const Student& b) { return a.name < b.name; });
  return students;
}

class ProgressBar {
 public:
  ProgressBar(size_t total, size_t done) : total_(std::max<size_t>(total, 1)), done_(done) {}
  void finished(const std::string& who) {
    std::lock_guard lock(mutex_);
    const size_t n = ++done_, width = 30, filled = n * width / total_;
    std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << n << "/" << total_ << " " << printable(who)
              << std::string(20, ' ') << std::flush;
  }

 private:
  size_t total_, done_;
  std::mutex mutex_;
};

}  // namespace

Expected<Shard> parse_shard(const std::string& text) {
  Shard s;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &s.index, &s.count, &extra) != 2 || s.count < 1 || s.index < 0 || s.index >= s.count)
    return make_error(ErrorCode::invalid_argument, "--shard takes I/N with 0 <= I < N (a job array's task index and size); got '" + text + "'");
  return s;
}

bool in_shard(const std::string& student, const Shard& shard) {
  return fnv1a64(student) % static_cast<std::uint64_t>(shard.count) == static_cast<std::uint64_t>(shard.index);
}

namespace {

// The shard's students no journal in `out` holds yet.
std::vector<Student> not_yet_graded(const std::vector<Student>& students, const fs::path& out) {
  const auto earlier = read_journals(out);
  std::vector<Student> todo;
  for (const auto& s : students)
    if (!earlier.contains(s.name)) todo.push_back(s);
  if (todo.size() < students.size())
    std::cerr << students.size() - todo.size() << " of " << students.size() << " already graded in " << out.string() << "; grading the other "
              << todo.size() << "\n";
  return todo;
}

// Grades `todo` on `concurrency` threads, recording each as it ends; the first error stops the
// others taking new students (those in flight are finished and recorded).
// `first_pass`, in the second pass: each student's first grade, whose cost the new line adds to
// its own (the class's cost counts both).
std::optional<Error> grade_all(const BatchOptions& o, const std::vector<Student>& todo, const GradeStudent& grade_student, Journal& journal,
                               ProgressBar& progress, const std::map<std::string, Entry>* first_pass = nullptr) {
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex first_error_mutex;
  std::optional<Error> first_error;
  const auto work = [&] {
    for (size_t i; !stop && (i = next++) < todo.size();) {
      const Student& s = todo[i];
      auto graded = grade_student(s);
      if (!graded) {
        std::lock_guard lock(first_error_mutex);
        if (!first_error) first_error = graded.take_error();
        stop = true;
        return;
      }
      if (first_pass && graded->first_grade_stands) {
        Entry entry = first_pass->at(s.name);
        entry.with_class = true;  // searched beside the class: nothing to try
        journal.append(entry);
        progress.finished(s.name);
        continue;
      }
      const auto& r = graded->report;
      // A student whose results cannot be written (a full disk) is not journaled: the batch
      // stops, and the next run grades them again.
      if (auto written = write_file(student_results(o.out, s.name), grade::to_gradescope(r, graded->seconds).dump(2) + "\n"); !written) {
        std::lock_guard lock(first_error_mutex);
        if (!first_error) first_error = written.take_error();
        stop = true;
        return;
      }
      Entry entry = entry_of(s.name, *graded);
      if (first_pass) {
        const Entry& first = first_pass->at(s.name);
        entry.renders += first.renders;
        entry.screened += first.screened;
        entry.with_class = true;
      }
      journal.append(entry);
      progress.finished(s.name);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::max(1, std::min<int>(o.concurrency, static_cast<int>(todo.size()))); ++t) threads.emplace_back(work);
  for (auto& t : threads) t.join();
  std::cerr << "\n";
  return first_error;
}

// The second pass: the shard's failing students no search repaired, not yet graded beside the
// class, graded again with the shard's passing students' programs; none where no one passes.
std::optional<Error> grade_with_class(const BatchOptions& o, const std::vector<Student>& students, const GradeWithClass& with_class,
                                      Journal& journal) {
  const auto entries = read_journals(o.out);
  std::vector<Student> passing, again;
  for (const auto& s : students) {
    const auto e = entries.find(s.name);
    if (e == entries.end()) continue;
    if (e->second.pass) passing.push_back(s);
    else if (e->second.unrepaired && !e->second.with_class) again.push_back(s);
  }
  if (passing.empty() || again.empty()) return std::nullopt;
  std::cerr << "searching " << again.size() << (again.size() == 1 ? " student's repair" : " students' repairs") << " again beside the "
            << passing.size() << " passing program" << (passing.size() == 1 ? "" : "s") << " of the class\n";
  ProgressBar progress(again.size(), 0);
  if (auto error = grade_all(o, again, with_class(passing), journal, progress, &entries)) return error;
  const auto after = read_journals(o.out);
  const auto repaired = std::count_if(again.begin(), again.end(), [&](const Student& s) { return !after.at(s.name).unrepaired; });
  std::cerr << "the class's programs repaired " << repaired << " of " << again.size() << "\n";
  return std::nullopt;
}

}  // namespace

int run_class_batch(const BatchOptions& o, const GradeStudent& grade_student, const GradeWithClass& with_class) {
  const auto students = students_of(o);
  if (students.empty()) {
    std::cerr << "error: no submission folders in " << o.submissions << (o.shard.count > 1 ? " for this shard" : "") << "\n";
    return 2;
  }
  fs::create_directories(o.out);
  const auto todo = not_yet_graded(students, o.out);
  Journal journal(o.out / journal_name(o.shard));
  if (!journal.ok()) {
    std::cerr << "error: cannot write the journal in " << o.out << "\n";
    return 1;
  }
  ProgressBar progress(students.size(), students.size() - todo.size());
  auto error = grade_all(o, todo, grade_student, journal, progress);
  if (!error && with_class) error = grade_with_class(o, students, with_class, journal);

  auto entries = read_journals(o.out);
  flag_shared_frames(entries, o.deliverable);
  if (auto summary = write_summary(o.out, entries); !summary && !error) error = summary.take_error();
  if (auto explanations = write_explanations(o.out, entries); !explanations && !error) error = explanations.take_error();
  if (error) {
    std::cerr << "error: the batch stopped: " << error->message << " [" << info(error->code).name << "]\n"
              << "run the same command again to grade the rest (finished students are kept)\n";
    return 1;
  }
  double total = 0;
  for (const auto& s : students)
    if (const auto e = entries.find(s.name); e != entries.end()) total += e->second.score;
  size_t flagged = 0;
  for (const auto& s : students)
    if (const auto e = entries.find(s.name); e != entries.end()) flagged += !e->second.flags.empty();
  for (const auto& [label, who] : by_explanation(entries))
    std::cerr << who.size() << (who.size() == 1 ? " student: " : " students: ") << printable(label) << "\n";
  if (flagged > 0) std::cerr << flagged << " students flagged for the TA: see the flags column of " << (o.out / "summary.csv").string() << "\n";
  say_cost(students, entries);
  std::cerr << "graded " << students.size() << " submissions" << (o.shard.count > 1 ? " in this shard" : "") << ", mean score "
            << total / static_cast<double>(students.size()) << "; results in " << o.out.string() << "/\n";
  return 0;
}

}  // namespace shadelab::cli
