// A student's HW2.ipynb read against the notebook the course handed out (sheet/notebook_reading.h):
// each case is the handed-out notebook edited as a student edits it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "course/course_import.h"
#include "course/course_reader.h"
#include "sheet/notebook_reading.h"
#include "support/files.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sheet::AnswerFound;

const fs::path kSource = SHADELAB_SOURCE_DIR;

json handed_out() { return json::parse(testkit::read_text(kSource / "assets/notebooks/hw2_handed_out.ipynb")); }

std::string text_of(const json& cell) {
  std::string out;
  for (const auto& line : cell["source"]) out += line.get<std::string>();
  return out;
}
void set_text(json& cell, const std::string& text) { cell["source"] = json::array({text}); }
json markdown(const std::string& text) { return {{"cell_type", "markdown"}, {"metadata", json::object()}, {"source", {text}}}; }

// The index of the first cell holding `words`.
size_t cell_with(const json& nb, const std::string& words) {
  for (size_t i = 0; i < nb["cells"].size(); ++i)
    if (text_of(nb["cells"][i]).find(words) != std::string::npos) return i;
  ADD_FAILURE() << "no cell holds " << words;
  return 0;
}

// The cell's text with its k-th placeholder block (0-based) replaced by `with`.
std::string replace_placeholder(std::string text, int k, const std::string& with) {
  const std::string block = "```\nYOUR ANSWER HERE\n```";
  size_t at = text.find(block);
  for (int i = 0; i < k; ++i) at = text.find(block, at + 1);
  return text.replace(at, block.size(), with);
}

// Students change the staff's paths in the code cells: that is not an answer.
void point_code_at_own_images(json& nb) {
  for (auto& cell : nb["cells"])
    if (cell["cell_type"] == "code") {
      std::string t = text_of(cell);
      for (size_t at; (at = t.find("_soln/")) != std::string::npos;) t.replace(at, 6, "/");
      set_text(cell, t);
    }
}

sheet::NotebookReading read(const json& nb, const course::Course& course = course::builtin_course()) {
  auto r = sheet::read_notebook(nb.dump(), course);
  EXPECT_TRUE(r) << r.error().message;
  return r ? *r : sheet::NotebookReading{};
}

TEST(NotebookReadingTest, AnAnswerWrittenInTheQuestionsOwnCellIsTheStudentsAlone) {
  json nb = handed_out();
  point_code_at_own_images(nb);
  const size_t webgl = cell_with(nb, "WebGL Questions");
  set_text(nb["cells"][webgl], replace_placeholder(text_of(nb["cells"][webgl]), 0, "$+z$ points at the viewer, and z is the blue channel."));
  const auto r = read(nb);
  ASSERT_EQ(r.answers.size(), 3u);
  EXPECT_TRUE(r.note.empty()) << r.note;
  EXPECT_EQ(r.answers[0].found, AnswerFound::written);
  EXPECT_EQ(r.answers[0].text, "$+z$ points at the viewer, and z is the blue channel.");
  EXPECT_NE(r.answers[0].question.find("why are the surfaces that face the viewer coloured blue"), std::string::npos) << "quoted from the notebook";
  EXPECT_EQ(r.answers[1].found, AnswerFound::placeholder_left);
  EXPECT_EQ(r.answers[2].found, AnswerFound::placeholder_left);
}

TEST(NotebookReadingTest, AnAnswerInANewCellAfterTheQuestion) {
  json nb = handed_out();
  const size_t camera = cell_with(nb, "focal length");
  nb["cells"].insert(nb["cells"].begin() + static_cast<long>(camera) + 1,
                     markdown("The subject stays the same size.\nThe background widens as the lens shortens."));
  const auto r = read(nb);
  EXPECT_EQ(r.answers[2].found, AnswerFound::written);
  EXPECT_EQ(r.answers[2].text, "The subject stays the same size.\nThe background widens as the lens shortens.");
  EXPECT_EQ(r.answers[0].found, AnswerFound::placeholder_left);
}

TEST(NotebookReadingTest, TheNotebookAsHandedOutAnswersNothing) {
  const auto r = read(handed_out());
  for (const auto& a : r.answers) {
    EXPECT_EQ(a.found, AnswerFound::placeholder_left) << a.question;
    EXPECT_TRUE(a.text.empty()) << a.text;
  }
  EXPECT_EQ(sheet::words_for(AnswerFound::placeholder_left, "HW2.ipynb"), "(unanswered: the placeholder is as handed out)");
  EXPECT_EQ(sheet::words_for(AnswerFound::not_found, course::builtin_course().notebook_name()), "(no answer under this question in HW2.ipynb)");
}

// The real student's notebook of the course's offering, in kind: the first answer in place of its
// placeholder, the other two placeholders deleted. The questions' own closing words stay theirs.
TEST(NotebookReadingTest, DeletedPlaceholdersAreUnansweredNotTheQuestionsClosingWords) {
  json nb = handed_out();
  const size_t webgl = cell_with(nb, "WebGL Questions"), camera = cell_with(nb, "focal length");
  set_text(nb["cells"][webgl], replace_placeholder(replace_placeholder(text_of(nb["cells"][webgl]), 1, ""), 0, "$n_z \\to$ blue"));
  set_text(nb["cells"][camera], replace_placeholder(text_of(nb["cells"][camera]), 0, ""));
  const auto r = read(nb);
  EXPECT_EQ(r.answers[0].text, "$n_z \\to$ blue");
  for (size_t q : {1u, 2u}) {
    EXPECT_EQ(r.answers[q].found, AnswerFound::none_written) << r.answers[q].text;
    EXPECT_TRUE(r.answers[q].text.empty()) << r.answers[q].text;
  }
  EXPECT_NE(r.answers[1].question.find("($k_a,k_d,k_s$ are colors"), std::string::npos);
  EXPECT_NE(r.answers[2].question.find("A few sentences should suffice."), std::string::npos);
}

TEST(NotebookReadingTest, AQuestionDeletedIsSaid) {
  json nb = handed_out();
  const size_t webgl = cell_with(nb, "WebGL Questions");
  std::string t = text_of(nb["cells"][webgl]);
  t = replace_placeholder(t, 0, "Blue is +z, toward the eye.");
  t = t.substr(0, t.find("2. How would you set"));  // the purple question and its placeholder gone
  set_text(nb["cells"][webgl], t);
  const auto r = read(nb);
  EXPECT_EQ(r.answers[0].text, "Blue is +z, toward the eye.");
  EXPECT_EQ(r.answers[1].found, AnswerFound::question_removed);
  EXPECT_EQ(r.answers[2].found, AnswerFound::placeholder_left);
}

// The colours the purple question asks for stay readable from what the student wrote.
TEST(NotebookReadingTest, ThePurpleAnswerKeepsItsColours) {
  json nb = handed_out();
  const size_t webgl = cell_with(nb, "WebGL Questions");
  set_text(nb["cells"][webgl], replace_placeholder(text_of(nb["cells"][webgl]), 1, "ambient (0.2, 0, 0.25)\ndiffuse (0.6, 0.1, 0.7)\nspecular (0.3, 0.5, 1)"));
  const auto r = read(nb);
  EXPECT_EQ(r.answers[1].text, "ambient (0.2, 0, 0.25)\ndiffuse (0.6, 0.1, 0.7)\nspecular (0.3, 0.5, 1)");
  EXPECT_EQ(r.answers[0].found, AnswerFound::placeholder_left);
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// Another course's folder with its own notebook (two questions of its own, one cell each):
// imported, its notebook kept and its questions read from it; its students' notebooks are read
// against it, and against the built-in course's they are not the same notebook (the sheet says so).
TEST(NotebookReadingTest, ANotebookFromAnotherCoursesImport) {
  const fs::path root = fs::temp_directory_path() / ("shadelab_notebook_import_" + std::to_string(::getpid()));
  fs::remove_all(root);
  write(root / "HW2/index.html", "<canvas id=\"glcanvas\" width=\"256\" height=\"256\"></canvas>\n");
  write(root / "HW2/src/hw2.js", "const uniformValues = { uAmbientColor: [0.2, 0.1, 0.1, 1.0] };\n");
  json theirs = {{"cells", {markdown("# Lab 3"), {{"cell_type", "code"}, {"source", {"show('frames_soln/*.png')"}}},
                            markdown("What does the half vector replace in Blinn-Phong?\n\n```\nYOUR ANSWER HERE\n```"),
                            markdown("Why is the specular term clamped at zero?\n\n```\nYOUR ANSWER HERE\n```")}},
                 {"nbformat", 4}};
  write(root / "HW2/Lab3.ipynb", theirs.dump(1));
  auto imported = course::import_course({root / "HW2", std::nullopt, root / "course/lab3.json", "lab3", ""});
  ASSERT_TRUE(imported) << imported.error().message;
  ASSERT_TRUE(imported->profile["notebook"].contains("handedOut"));
  EXPECT_EQ(imported->profile["notebook"]["handedOut"], "lab3.handed_out.ipynb");
  ASSERT_EQ(imported->profile["notebook"]["questions"].size(), 2u);
  EXPECT_EQ(imported->profile["notebook"]["questions"][1]["text"], "Why is the specular term clamped at zero?");
  for (const auto& [name, text] : imported->derived_files) write(root / "course" / name, text);
  write(root / "course/lab3.json", imported->profile.dump(2));
  auto lab3 = course::load_course_file(root / "course/lab3.json");
  ASSERT_TRUE(lab3) << lab3.error().message;

  json student = theirs;
  set_text(student["cells"][3], "Why is the specular term clamped at zero?\n\nA negative cosine would darken the far side.");
  auto r = read(student, *lab3);
  ASSERT_EQ(r.answers.size(), 2u);
  EXPECT_EQ(r.answers[0].found, AnswerFound::placeholder_left);
  EXPECT_EQ(r.answers[1].text, "A negative cosine would darken the far side.");

  r = read(student);  // the built-in course's notebook is not this one
  EXPECT_NE(r.note.find("of the handed-out notebook's text, so what the student added cannot be told"), std::string::npos) << r.note;
  fs::remove_all(root);
}

}  // namespace
}  // namespace shadelab
