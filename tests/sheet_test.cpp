// The submission sheet (`shadelab sheet`, server/sheet/) read back as a reader would: the PDF's
// text (pdftotext) and its first page as pixels (pdftoppm), the HTML page, identical bytes for
// the same folder; and the text helpers the layouts share.
#include <gtest/gtest.h>

#include <cctype>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "image/encode.h"
#include "sheet/notebook_reading.h"
#include "sheet/notebook.h"
#include "sheet/sheet.h"
#include "support/files.h"
#include "support/http_fixture.h"
#include "support/openapi_check.h"
#include "support/run_command.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using namespace shadelab;

namespace {

const fs::path kSource = SHADELAB_SOURCE_DIR;

using Ran = testkit::CommandRun;
Ran run(const std::string& command) { return testkit::run_command(command); }

// A small PNG of one colour, for an image a student hands in.
std::string solid_png(int width, int height, std::uint8_t red) {
  auto img = image::Image::blank(width, height, image::PixelType::u8);
  for (size_t i = 0; i < img.bytes.size(); i += 4) img.bytes[i] = red, img.bytes[i + 3] = 255;
  const auto png = *image::encode_png(img);
  return {png.begin(), png.end()};
}

// The line of `needle` in `text`, 1-based.
int line_of(const std::string& text, const std::string& needle) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(text.find(needle)), '\n'));
}

// One student's folder laid out as the course's (src/shaders/, images/), made once: normals
// right, diffuse handed in as its nine saved frames, the specular stage with a compile error, two
// of the Blender images (camera_100.png missing), short answers; the sheet made twice.
class SheetTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("shadelab_sheet_" + std::to_string(::getpid())));
    fs::create_directories(*dir_ / "HW2/src/shaders");
    const auto copy = [](const std::string& preset, const std::string& stage, const std::string& as) {
      std::ofstream(*dir_ / "HW2/src/shaders" / as) << testkit::read_text(kSource / "shaders" / (preset + "_" + stage + ".js"));
    };
    copy("normals", "vert", "starter_vert.js");
    copy("normals", "frag", "starter_frag.js");
    copy("specular", "vert", "phong_vert.js");
    std::string frag = testkit::read_text(kSource / "shaders/specular_frag.js");
    frag.replace(frag.find("fragColor = color;"), 18, "fragColor = color * undefinedThing;");
    std::ofstream(*dir_ / "HW2/src/shaders/phong_frag.js") << frag;
    error_line_ = line_of(frag, "fragColor = color * undefinedThing;");
    // The normals deliverable's saved frames, at the canvas's size, beside its code.
    made_.push_back(run(std::string(SHADELAB_CLI) + " render --preset normals --angles " + testkit::kPageAngles + " --frames-dir " +
                        (*dir_ / "HW2/images").string()));
    // The diffuse deliverable as the browser saved it: nine frames, no code.
    made_.push_back(run(std::string(SHADELAB_CLI) + " render --preset diffuse --size 96x96 --angles " + testkit::kPageAngles +
                        " --frames-dir " + (*dir_ / "HW2/images").string()));
    for (const auto& [name, red] : {std::pair{"camera_25.png", 200}, {"camera_50.png", 150}, {"eevee0001.png", 100}})
      std::ofstream(*dir_ / "HW2/images" / name, std::ios::binary) << solid_png(64, 36, static_cast<std::uint8_t>(red));
    std::ofstream(*dir_ / "answers.txt") << "The normal's z is blue, and +z faces the viewer & interpolates <colours>.\n\nA longer lens flattens.\n";
    for (const char* name : {"a", "b"})
      made_.push_back(run(std::string(SHADELAB_CLI) + " sheet " + (*dir_ / "HW2").string() + " -o " + (*dir_ / name).string() +
                          ".pdf --html " + (*dir_ / name).string() + ".html --answers " + (*dir_ / "answers.txt").string() +
                          " --scene " + (kSource / "assets/scenes/two_objects.json").string() + " --title 'HW2: Ada Lovelace'"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  void SetUp() override {
    for (const auto& r : made_) ASSERT_EQ(r.status, 0) << r.output;
  }
  static std::string pdf_text(int first_page = 0, int last_page = 0) {
    std::string range = first_page ? " -f " + std::to_string(first_page) + " -l " + std::to_string(last_page) : "";
    return run("pdftotext -layout" + range + " " + (*dir_ / "a.pdf").string() + " -").output;
  }
  static fs::path* dir_;
  static std::vector<Ran> made_;
  static int error_line_;
};
fs::path* SheetTest::dir_ = nullptr;
std::vector<Ran> SheetTest::made_;
int SheetTest::error_line_ = 0;

std::string title(const std::string& checkpoint) { return testkit::course().checkpoint(checkpoint)->checkpoint->title; }

}  // namespace

// The notebook's order: the normals grid and the starter's code, the diffuse grid (its saved
// frames), the specular grid and the phong code, the questions and answers, the Blender images.
TEST_F(SheetTest, ThePdfFollowsTheNotebooksOrderWithEachVerdictCodeAndTheAnswers) {
  const std::string text = pdf_text();
  const auto& course = testkit::course();
  std::vector<std::string> in_order = {"HW2: Ada Lovelace", "1. " + title("normals"), "1 / 1: matches the reference under the page's light",
                                       "matches the reference exactly",
                                       "src/shaders/starter_vert.js", "vColor = vec4(normalize(abs(normal.xyz)), 1.0);",
                                       "2. " + title("diffuse"), "handed in as images: 9 of 9 saved frames (hw2_diffuse_0.png, ...)",
                                       "the frames the student saved", "3. " + title("specular"), "0 / 1: compile error at phong_frag.js line",
                                       "fragColor = color * undefinedThing;", "Questions"};
  for (const auto& q : sheet::quoted_questions(course)) in_order.push_back(q.substr(0, 40));  // as the handed-out notebook asks them
  for (const std::string s : {"Answers", "interpolates <colours>.", "A longer lens flattens."}) in_order.push_back(s);
  for (const auto& image : course.images) in_order.push_back(image.title + " (" + image.file + ")");
  in_order.push_back("Blender: two_objects.json (lens 50 mm, 640 x 480)");
  size_t at = 0;
  for (const auto& expected : in_order) {
    const size_t found = text.find(expected, at);
    ASSERT_NE(found, std::string::npos) << "'" << expected << "' missing or out of order\n" << text.substr(0, 3000);
    at = found;
  }
  for (const char* expected : {"not in the submission", "both objects fully in the image", "Suzanne: fully in the image, 100% of it in frame, covers",
                               "Suzanne: base colour (0.80, 0.10, 0.10), metallic 1.00, roughness 0.20"})
    EXPECT_NE(text.find(expected), std::string::npos) << expected;
  EXPECT_NE(text.find("Dolly zoom: 100 mm (images/camera_100.png)\nnot in the submission"), std::string::npos) << "the missing image, named";
  EXPECT_NE(run("pdfinfo " + (*dir_ / "a.pdf").string()).output.find("Title:           HW2: Ada Lovelace"), std::string::npos);
}

// The grid and the start of the code that made it are on the same page, and the grid is drawn:
// the first page, rasterised, has the bunnies' colours where the grid is.
TEST_F(SheetTest, TheGridIsDrawnOnThePageOfItsCode) {
  const std::string page1 = pdf_text(1, 1);
  EXPECT_NE(page1.find("1. " + title("normals")), std::string::npos);
  EXPECT_NE(page1.find("src/shaders/starter_vert.js"), std::string::npos) << page1;
  ASSERT_EQ(run("pdftoppm -r 36 -f 1 -l 1 " + (*dir_ / "a.pdf").string() + " " + (*dir_ / "page").string()).status, 0);
  std::string ppm;
  for (const auto& e : fs::directory_iterator(*dir_))
    if (e.path().filename().string().starts_with("page")) ppm = testkit::read_text(e.path());
  ASSERT_TRUE(ppm.starts_with("P6")) << "pdftoppm writes binary PPM";
  int width = 0, height = 0, max = 0, header = 0;
  ASSERT_EQ(std::sscanf(ppm.c_str(), "P6 %d %d %d%n", &width, &height, &max, &header), 3);
  const std::string pixels = ppm.substr(static_cast<size_t>(header) + 1);
  ASSERT_EQ(pixels.size(), static_cast<size_t>(width * height * 3));
  int black = 0, coloured = 0;
  for (size_t i = 0; i < pixels.size(); i += 3) {
    const int r = static_cast<unsigned char>(pixels[i]), g = static_cast<unsigned char>(pixels[i + 1]),
              b = static_cast<unsigned char>(pixels[i + 2]);
    black += r + g + b < 30;
    coloured += std::max({r, g, b}) - std::min({r, g, b}) > 80;  // the normal-coloured bunnies
  }
  EXPECT_GT(black, width * height / 10) << "the grid's black background";
  EXPECT_GT(coloured, 500) << "the bunnies";
}

// A deliverable with code and saved frames: the saved frames' grid beside the code's, the lag found
// and both verdicts (against the reference, against the code) in the text; the first page has the
// normal-coloured bunnies in both halves of the page.
TEST_F(SheetTest, SavedFramesAreShownBesideTheCodesGridWithTheirVerdicts) {
  const std::string page1 = pdf_text(1, 1);
  // The verdicts wrap at the page's width: read as one run of words.
  std::string words;
  for (const char c : page1)
    if (!std::isspace(static_cast<unsigned char>(c)) || (!words.empty() && words.back() != ' ')) words += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
  for (const std::string expected : {"the frames the student saved", "rendered from the student's code",
                                     "saved frames: 1 / 1: matches the reference", "degrees behind their nominal angles",
                                     "saved frames against the code: the saved frames are what your code renders"})
    EXPECT_NE(words.find(expected), std::string::npos) << expected << "\n" << page1;
  EXPECT_EQ(words.find("FLAGGED"), std::string::npos) << "frames from a page's run are not flagged";
  // The diffuse frames were saved at 96 x 96: graded, and the size named.
  EXPECT_NE(pdf_text().find("hw2_diffuse_0.png is 96 x 96; the course's canvas is 512 x 512"), std::string::npos);
  ASSERT_EQ(run("pdftoppm -r 36 -f 1 -l 1 " + (*dir_ / "a.pdf").string() + " " + (*dir_ / "halves").string()).status, 0);
  std::string ppm;
  for (const auto& e : fs::directory_iterator(*dir_))
    if (e.path().filename().string().starts_with("halves")) ppm = testkit::read_text(e.path());
  int width = 0, height = 0, max = 0, header = 0;
  ASSERT_EQ(std::sscanf(ppm.c_str(), "P6 %d %d %d%n", &width, &height, &max, &header), 3);
  const std::string pixels = ppm.substr(static_cast<size_t>(header) + 1);
  int left = 0, right = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
      const int r = static_cast<unsigned char>(pixels[i]), g = static_cast<unsigned char>(pixels[i + 1]), b = static_cast<unsigned char>(pixels[i + 2]);
      if (std::max({r, g, b}) - std::min({r, g, b}) > 80) (x < width / 2 ? left : right) += 1;
    }
  EXPECT_GT(left, 300) << "the saved frames' bunnies";
  EXPECT_GT(right, 300) << "the code's bunnies";
}

TEST_F(SheetTest, TheSameFolderGivesTheSameBytes) {
  EXPECT_EQ(testkit::read_text(*dir_ / "a.pdf"), testkit::read_text(*dir_ / "b.pdf"));
  EXPECT_EQ(testkit::read_text(*dir_ / "a.html"), testkit::read_text(*dir_ / "b.html"));
}

TEST_F(SheetTest, TheHtmlPageHasTheSameSectionsWithTheErrorLineMarked) {
  const std::string html = testkit::read_text(*dir_ / "a.html");
  EXPECT_NE(html.find("<title>HW2: Ada Lovelace</title>"), std::string::npos);
  EXPECT_NE(html.find("<img alt=\"3x3 grid of normals\" src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);
  EXPECT_NE(html.find("<img alt=\"3x3 grid of diffuse\" src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos) << "the saved frames";
  EXPECT_NE(html.find("(no grid: the shaders did not render)"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"marked\"><span class=\"n\">" + std::to_string(error_line_) +
                      "</span>    fragColor = color * undefinedThing;</span>"),
            std::string::npos)
      << "the line the compile error names, marked";
  EXPECT_NE(html.find("<img alt=\"Dolly zoom: 25 mm\" src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);
  EXPECT_NE(html.find("interpolates &lt;colours&gt;."), std::string::npos) << "the answers, escaped";
  EXPECT_NE(html.find("\">Suzanne</div>"), std::string::npos) << "Suzanne's framing box";
  EXPECT_NE(html.find("<div class=\"box in\""), std::string::npos);
}

TEST(SheetTextTest, PrintableTextAndThePointedLines) {
  EXPECT_EQ(sheet::printable("a\tb\r\nc\x01\xff é"), "a    b\nc?? é");
  grade::Report r;
  r.diagnostics = {{"fragment", "phong_frag.js", 12, 3, "error", "x"}, {"fragment", "phong_frag.js", 0, 0, "error", "y"},
                   {"vertex", "phong_vert.js", 4, 1, "warning", "z"}};
  EXPECT_EQ(sheet::lines_pointed_at(r, "shaders/phong_frag.js"), std::set<int>{12});
  EXPECT_EQ(sheet::lines_pointed_at(r, "phong_vert.js"), std::set<int>{4});
  r.score = 0;
  r.messages = {"specular highlight missing"};
  EXPECT_EQ(sheet::verdict(r), "0 / 1: specular highlight missing");
}

// The notebook read for answers: the cells under each question, in any of the ways students write them.
TEST(NotebookTest, AnswersAreTheCellsUnderEachQuestion) {
  const auto& questions = testkit::course().questions;
  const nlohmann::json nb = {{"nbformat", 4}, {"cells", {
      {{"cell_type", "markdown"}, {"source", "# HW2"}},
      {{"cell_type", "markdown"}, {"source", {"**Q1.** Why are the surfaces facing you blue?\n"}}},
      {{"cell_type", "code"}, {"source", "show_grid('normals')"}},
      {{"cell_type", "markdown"}, {"source", {"Because +z points at the viewer,\n", "and z is blue."}}},
      {{"cell_type", "markdown"}, {"source", "**Q2.** A purple bunny?"}},
      {{"cell_type", "markdown"}, {"source", "Ambient (0.15, 0, 0.2); uDiffuseColor = vec4(0.6, 0.1, 0.7, 1.0); specular: 80, 140, 255"}},
      {{"cell_type", "markdown"}, {"source", "## Blender\nWhat does doubling the focal length and the distance do?\n\nThe subject keeps its size."}}}}};
  auto answers = sheet::notebook_answers(nb.dump(), questions);
  ASSERT_TRUE(answers.ok()) << answers.error().message;
  ASSERT_EQ(answers->size(), 3u);
  EXPECT_EQ((*answers)[0], "Because +z points at the viewer,\nand z is blue.");  // the code cell between is skipped
  EXPECT_EQ((*answers)[2], "The subject keeps its size.");                       // written in the question's own cell
  const auto colours = sheet::colours_in((*answers)[1]);
  ASSERT_TRUE(colours.has_value()) << (*answers)[1];
  EXPECT_EQ(colours->ambient, (std::array<double, 3>{0.15, 0, 0.2}));
  EXPECT_EQ(colours->diffuse, (std::array<double, 3>{0.6, 0.1, 0.7}));  // not the 4 of vec4
  EXPECT_NEAR(colours->specular[1], 140 / 255.0, 1e-12);                 // 0-255 values scaled
  EXPECT_FALSE(sheet::colours_in("ambient purple, diffuse purple, specular blue").has_value());
  // The purple question's cell holds "blue" too ("blue-ish highlights"): it is still the purple
  // question's, and the blue question, not asked in this notebook, has no answer.
  const nlohmann::json only_purple = {{"cells", {
      {{"cell_type", "markdown"}, {"source", "How would you get a purple bunny with blue-ish highlights? RGB values."}},
      {{"cell_type", "markdown"}, {"source", "Ambient: [0.25, 0.05, 0.3]"}}}}};
  auto purple_only = sheet::notebook_answers(only_purple.dump(), questions);
  ASSERT_TRUE(purple_only.ok());
  EXPECT_EQ((*purple_only)[0], "");
  EXPECT_EQ((*purple_only)[1], "Ambient: [0.25, 0.05, 0.3]");
  EXPECT_FALSE(sheet::notebook_answers("{\"not\": \"a notebook\"}", questions).ok());
  EXPECT_FALSE(sheet::notebook_answers("\x89PNG", questions).ok());
}

// POST /api/sheet: the same sheet from files sent with their paths, through the real server.
class SheetApiTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new testkit::RunningService(testkit::test_config()); }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_TRUE(server_->ok()) << server_->failure; }

  static nlohmann::json files() {
    nlohmann::json f = nlohmann::json::object();
    for (const auto& [preset, as] : {std::pair{"normals", "starter"}, std::pair{"specular", "phong"}})
      for (const char* stage : {"vert", "frag"})
        f[std::string("HW2/src/shaders/") + as + "_" + stage + ".js"] =
            testkit::read_text(kSource / "shaders" / (std::string(preset) + "_" + stage + ".js"));
    return f;
  }
  static httplib::Result post(const nlohmann::json& body) {
    return server_->client().Post("/api/sheet", body.dump(), "application/json");
  }
  static testkit::RunningService* server_;
};
testkit::RunningService* SheetApiTest::server_ = nullptr;

// The answers come from the student's HW2.ipynb, the purple bunny rendered in the colours they wrote.
TEST_F(SheetApiTest, TheNotebooksAnswersAndThePurpleBunnyInTheStudentsColours) {
  nlohmann::json f = files();
  const nlohmann::json nb = {{"cells", {
      {{"cell_type", "markdown"}, {"source", "Why is the bunny blue where it faces you?"}},
      {{"cell_type", "markdown"}, {"source", "The normal's z is blue."}},
      {{"cell_type", "markdown"}, {"source", "How do you make a purple bunny with blue-ish highlights?"}},
      {{"cell_type", "markdown"}, {"source", "ambient = (0.2, 0.0, 0.25), diffuse = (0.6, 0.1, 0.7), specular = (0.3, 0.5, 1.0)"}}}}};
  f["HW2/HW2.ipynb"] = nb.dump();
  auto r = post({{"files", f}, {"format", "html"}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const std::string& html = r->body;
  const size_t blue = html.find("The normal's z is blue."), purple = html.find("ambient = (0.2, 0.0, 0.25)");
  ASSERT_NE(blue, std::string::npos) << html.substr(html.find("id=\"questions\""), 1500);
  ASSERT_NE(purple, std::string::npos);
  EXPECT_LT(blue, purple);
  EXPECT_NE(html.find("the bunny in your colours: ambient (0.20, 0.00, 0.25), diffuse (0.60, 0.10, 0.70), specular (0.30, 0.50, 1.00)"),
            std::string::npos);
  EXPECT_NE(html.find("(no answer under this question in HW2.ipynb)"), std::string::npos) << "the Blender question, unanswered";
  EXPECT_NE(html.find("HW2.ipynb keeps 0% of the handed-out notebook's text"), std::string::npos) << "not the handed-out notebook, and said";
  // The render: a purple bunny (red and blue over green) on the page's black.
  const std::string marker = "alt=\"the bunny in the answer's colours\" src=\"data:image/png;base64,";
  const size_t at = html.find(marker);
  ASSERT_NE(at, std::string::npos);
  const size_t begin = at + marker.size();
  const auto png = base64_decode(html.substr(begin, html.find('"', begin) - begin));
  ASSERT_TRUE(png.has_value());
  const image::Image img = testkit::decode(std::vector<std::uint8_t>(png->begin(), png->end()));
  double sum[3] = {0, 0, 0};
  int lit = 0;
  for (size_t i = 0; i < img.bytes.size(); i += 4)
    if (img.bytes[i] + img.bytes[i + 1] + img.bytes[i + 2] > 30) {
      ++lit;
      for (int c = 0; c < 3; ++c) sum[c] += img.bytes[i + c];
    }
  ASSERT_GT(lit, img.width * img.height / 50) << "the bunny is drawn";
  EXPECT_GT(sum[0], 1.5 * sum[1]);
  EXPECT_GT(sum[2], 1.5 * sum[1]);
}

TEST_F(SheetApiTest, AJsonBodyGivesThePdfAndTheHtmlPage) {
  auto pdf = post({{"files", files()}, {"answers", "Phong lights each fragment."}, {"title", "HW2: Grace Hopper"}});
  ASSERT_TRUE(pdf);
  ASSERT_EQ(pdf->status, 200) << pdf->body.substr(0, 400);
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_TRUE(pdf->body.starts_with("%PDF-"));
  testkit::expect_conforms(*pdf, "/api/sheet", "post");
  const fs::path file = fs::temp_directory_path() / ("shadelab_sheet_api_" + std::to_string(::getpid()) + ".pdf");
  std::ofstream(file, std::ios::binary) << pdf->body;
  const std::string text = run("pdftotext -layout " + file.string() + " -").output;
  fs::remove(file);
  for (const char* expected : {"HW2: Grace Hopper", "HW2/src/shaders/starter_vert.js", "HW2/src/shaders/phong_frag.js", "Phong lights each fragment."})
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text.substr(0, 1500);
  // Both checkpoints' code passes; without saved frames, each scores what Gradescope gives the
  // same hand-in: the code's shares of its points (normals: the code's 1 of 4; specular: the code's
  // and the hidden light's 2 of 5), the rest named.
  const std::string flat = std::regex_replace(text, std::regex("\\s+"), " ");
  EXPECT_NE(flat.find("0.25 / 1: matches the reference under the page's light; not graded, nothing handed in for it: saved frames (0.5), saved frames "
                      "made by your code (0.25)"), std::string::npos) << flat.substr(0, 1500);
  EXPECT_NE(flat.find("0.4 / 1: matches the reference under the page's light; not graded, nothing handed in for it: saved frames (0.4), saved frames "
                      "made by your code (0.2)"), std::string::npos) << flat.substr(0, 1500);

  auto html = post({{"files", files()}, {"format", "html"}});
  ASSERT_TRUE(html);
  ASSERT_EQ(html->status, 200) << html->body.substr(0, 400);
  EXPECT_EQ(html->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(html->body.find("<h2>3. " + title("specular") + "</h2>"), std::string::npos);
  auto with_image = post({{"files", files()}, {"format", "html"}, {"images", {{"HW2/images/camera_25.png", base64_encode(solid_png(8, 8, 90))}}}});
  ASSERT_TRUE(with_image);
  ASSERT_EQ(with_image->status, 200) << with_image->body.substr(0, 400);
  EXPECT_NE(with_image->body.find("<img alt=\"Dolly zoom: 25 mm\" src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);
  auto again = post({{"files", files()}, {"format", "html"}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->body, html->body) << "the same files give the same bytes";
}

// The handed-out notebook as a student fills it in: the first answer in place of its placeholder,
// the colours in place of the second, the camera question left. What they wrote is shown under the
// question quoted from the notebook, and only that.
TEST_F(SheetApiTest, TheAnswersAreWhatTheStudentWroteInTheHandedOutNotebook) {
  nlohmann::json nb = nlohmann::json::parse(testkit::read_text(kSource / "assets/notebooks/hw2_handed_out.ipynb"));
  const std::string block = "```\nYOUR ANSWER HERE\n```";
  for (auto& cell : nb["cells"]) {
    std::string text;
    for (const auto& line : cell["source"]) text += line.get<std::string>();
    if (text.find("WebGL Questions") == std::string::npos) continue;
    text.replace(text.find(block), block.size(), "The normal's z is blue, and +z faces the eye.");
    text.replace(text.find(block), block.size(), "ambient = (0.2, 0.0, 0.25), diffuse = (0.6, 0.1, 0.7), specular = (0.3, 0.5, 1.0)");
    cell["source"] = nlohmann::json::array({text});
  }
  nlohmann::json f = files();
  f["HW2/HW2.ipynb"] = nb.dump();
  auto r = post({{"files", f}, {"format", "html"}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body.substr(0, 400);
  const std::string questions = r->body.substr(r->body.find("<section id=\"questions\">"));
  EXPECT_EQ(questions.find("handed-out notebook's text"), std::string::npos) << "read against the handed-out notebook";
  EXPECT_NE(questions.find("<p>The normal's z is blue, and +z faces the eye.</p>"), std::string::npos) << questions.substr(0, 1500);
  EXPECT_NE(questions.find("the bunny in your colours: ambient (0.20, 0.00, 0.25)"), std::string::npos);
  EXPECT_NE(questions.find("(unanswered: the placeholder is as handed out)"), std::string::npos);
  EXPECT_EQ(questions.find("<p>($k_a,k_d,k_s$"), std::string::npos) << "the question's own words are no answer";
  EXPECT_NE(questions.find("<p class=\"note\">2. How would you set the ambient, diffuse and specular colours"), std::string::npos)
      << "quoted from the notebook";
}

// The dolly zoom's images checked on the page as on Gradescope (GradescopeTest's twin): one image
// saved for two cameras is named, in the same words.
TEST_F(SheetApiTest, TheDollyZoomsCamerasAreCheckedOnTheSheet) {
  const auto blender = [](const std::string& lens) {
    return base64_encode(testkit::read_text(kSource / "tests/blender_half" / ("blender_camera_" + lens + ".png")));
  };
  auto r = post({{"files", files()},
                 {"format", "html"},
                 {"images", {{"HW2/images/camera_25.png", blender("25")}, {"HW2/images/camera_50.png", blender("50")},
                             {"HW2/images/camera_100.png", blender("50")}}}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body.substr(0, 400);
  for (const char* line : {"<p class=\"pass\">0 / 0 (for the TA): matches the handout's camera (a 25 mm lens at (0, -4, 0);",
                           "<p class=\"fail\">0 / 0 (for the TA): the same image as images/camera_50.png: shows a 50 mm lens at (0, -8, 0)"})
    EXPECT_NE(r->body.find(line), std::string::npos) << line << "\n" << r->body.substr(r->body.find("Dolly zoom"), 3000);
}

// The framing report on the sheet follows the scene: Suzanne moved out of the frame is named.
TEST_F(SheetApiTest, AnObjectMovedOutOfFrameChangesTheVerdict) {
  nlohmann::json scene = nlohmann::json::parse(testkit::read_text(kSource / "assets/scenes/two_objects.json"));
  nlohmann::json moved = scene;
  for (auto& o : moved["objects"])
    if (o["name"] == "Suzanne") o["location"][0] = o["location"][0].get<double>() - 3.0;
  auto r = post({{"files", files()}, {"format", "html"}, {"scenes", {{{"name", "as set"}, {"scene", scene}}, {{"name", "moved"}, {"scene", moved}}}}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body.substr(0, 400);
  const size_t first = r->body.find("<h2>Blender: as set"), second = r->body.find("<h2>Blender: moved");
  ASSERT_NE(first, std::string::npos);
  ASSERT_NE(second, std::string::npos);
  EXPECT_NE(r->body.substr(first, second - first).find("both objects fully in the image"), std::string::npos);
  EXPECT_NE(r->body.substr(second).find("not fully in the image: Suzanne"), std::string::npos) << r->body.substr(second, 600);
  EXPECT_NE(r->body.substr(second).find("<div class=\"box out\""), std::string::npos);
}

TEST_F(SheetApiTest, MultipartPartsNamedByTheirPaths) {
  httplib::MultipartFormDataItems items{{"format", "html", "", ""}};
  const nlohmann::json all = files();
  for (const auto& [path, text] : all.items())
    items.push_back({path, text.get<std::string>(), path.substr(path.rfind('/') + 1), "text/javascript"});
  auto r = server_->client().Post("/api/sheet", items);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body.substr(0, 400);
  EXPECT_NE(r->body.find("<h3>HW2/src/shaders/starter_frag.js</h3>"), std::string::npos);
}

TEST_F(SheetApiTest, BadRequestsAreProblems) {
  nlohmann::json outside = files();
  outside["../../etc/passwd"] = "x";
  for (const auto& [body, fragment] : std::vector<std::pair<nlohmann::json, std::string>>{
           {nlohmann::json::object(), "files: send the student's shader files"},
           {{{"files", outside}}, "'../../etc/passwd' is not a path inside the submission"},
           {{{"files", files()}, {"format", "docx"}}, "format: pdf or html"},
           {{{"files", {{"a.js", 3}}}}, "files.a.js: expected the file's text"},
           {{{"files", files()}, {"scenes", {{{"name", "x"}}}}}, "scenes[0]: expected {"},
           {{{"files", files()}, {"images", {{"images/a.png", "not base64!"}}}}, "images.images/a.png: expected the file's bytes in base64"}}) {
    auto r = post(body);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json");
    EXPECT_NE(r->body.find(fragment), std::string::npos) << r->body;
    testkit::expect_conforms(*r, "/api/sheet", "post");
  }
}

