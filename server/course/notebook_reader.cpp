#include "course/notebook_reader.h"

#include <regex>

#include "course/notebook_lines.h"
#include "scene/scene_description.h"

namespace shadelab::course {

namespace {

class NotebookReader {
 public:
  NotebookReader(const FileSource& files, Course& course, const std::string* error) : files_(files), course_(course), error_(error) {}

  // The scene a hand-in image is checked against: a scene file (docs/scenes.md) beside the profile.
  std::optional<scene::SceneDescription> checked_scene(const JsonReader& i, const std::string& path, std::string& source) {
    if (failed()) return std::nullopt;
    auto read = files_.read(path);
    if (!read) {
      i.fail_at(i.at("scene"), read.error().message);
      return std::nullopt;
    }
    source = source_of(*read);
    const auto j = nlohmann::json::parse(read->bytes, nullptr, false);
    auto parsed = j.is_discarded() ? Expected<scene::SceneDescription>(make_error(ErrorCode::invalid_argument, "not JSON"))
                                   : scene::parse_scene(j);
    if (!parsed) {
      i.fail_at(i.at("scene"), path + " is not a scene: " + parsed.error().message);
      return std::nullopt;
    }
    return std::move(*parsed);
  }

  // The notebook as handed out, beside the profile; its placeholder must mark at least one answer's place.
  std::optional<HandedOutNotebook> handed_out(const JsonReader& n) {
    HandedOutNotebook out{n.text("handedOut", ""), "", "", n.text("placeholder", "YOUR ANSWER HERE")};
    if (failed()) return std::nullopt;
    auto read = files_.read(out.file);
    if (!read) {
      n.fail_at(n.at("handedOut"), read.error().message);
      return std::nullopt;
    }
    out.source = source_of(*read);
    out.text = std::move(read->bytes);
    if (out.placeholder.empty() || out.text.find(out.placeholder) == std::string::npos)
      n.fail_at(n.at("handedOut"), out.file + " has no '" + out.placeholder + "' marking an answer's place (notebook.placeholder)");
    return out;
  }

  // Each question looked for in the notebook is one the handed-out notebook asks.
  void questions_placed(const JsonReader& n, const HandedOutNotebook& handed_out) {
    if (failed()) return;
    auto cells = notebook_cells(handed_out.text);
    auto placed = cells ? placed_questions(notebook_lines(*cells), handed_out.placeholder) : Expected<std::vector<PlacedQuestion>>(cells.take_error());
    if (!placed) return n.fail_at(n.at("handedOut"), handed_out.file + ": " + placed.error().message);
    const std::vector<int> at = match_questions(course_.questions, *placed);
    for (size_t q = 0; q < course_.questions.size(); ++q)
      if (!course_.questions[q].cell.empty() && at[q] < 0)
        return n.fail_at(n.at("questions"), "question '" + course_.questions[q].id + "': no question of " + handed_out.file + " holds '" +
                                                course_.questions[q].cell + "' (its `cell` words)");
  }

  // The notebook's questions and the images handed in with it (both optional).
  void read(const JsonReader& r) {
    if (!r.has("notebook")) return;
    const JsonReader n = r.object("notebook");
    n.only({"file", "questions", "images", "handedOut", "placeholder"});
    course_.notebook_file = n.text("file", "");
    if (!course_.notebook_file.empty() && (!course_.notebook_file.ends_with(".ipynb") || course_.notebook_file.find('/') != std::string::npos))
      n.fail_at(n.at("file"), "expected the notebook's file name, ending in .ipynb");
    if (n.has("handedOut")) course_.handed_out = handed_out(n);
    for (const JsonReader& q : n.objects("questions")) {
      q.only({"id", "text", "cell", "renderColours"});
      q.require("id") && q.require("text");
      course_.questions.push_back({q.text("id", ""), q.text("text", ""), q.text("cell", ""), q.text("renderColours", "")});
      const std::string& renders = course_.questions.back().render_colours;
      if (!renders.empty() && !course_.preset(renders)) q.fail_at(q.at("renderColours"), "'" + renders + "' is not one of the course's presets");
    }
    if (course_.handed_out) questions_placed(n, *course_.handed_out);
    for (const JsonReader& i : n.objects("images")) {
      i.only({"file", "title", "scene", "objects", "points"});
      i.require("file") && i.require("title");
      HandInImage image{i.text("file", ""), i.text("title", ""), i.text("scene", ""), {}, {},
                        i.integer("objects", 0, 0, 100), i.number("points", 0, 0, 1000)};
      if (i.has("objects") && i.has("scene")) i.fail_at(i.at("objects"), "an image is checked against its scene or for its objects, not both");
      if (i.has("file") && (!std::regex_match(image.file, std::regex("[A-Za-z0-9_./-]{1,200}")) || !image.file.ends_with(".png") ||
                            image.file.find("..") != std::string::npos || image.file.starts_with("/")))
        i.fail_at(i.at("file"), "expected a relative path of a .png file in the student's folder");
      if (!image.scene_file.empty()) image.scene = checked_scene(i, image.scene_file, image.scene_source);
      course_.images.push_back(std::move(image));
    }
  }


 private:
  bool failed() const { return error_ && !error_->empty(); }

  const FileSource& files_;
  Course& course_;
  const std::string* error_;  // the profile's first problem (JsonReader): checks that need files wait for none
};

}  // namespace

void read_notebook(const JsonReader& profile, const FileSource& files, Course& course) {
  NotebookReader(files, course, profile.error_sink()).read(profile);
}

}  // namespace shadelab::course
