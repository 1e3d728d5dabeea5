// POST /api/sheet: the submission sheet (server/sheet/) from a student's files, as a PDF or one
// HTML page. The body names each file by its path in the student's folder:
//
// | form      | files                                                 | other fields               |
// |-----------|-------------------------------------------------------|----------------------------|
// | JSON      | "files": {"src/shaders/starter_vert.js": "<source>"}, | answers, title, format,    |
// |           | "images": {"images/camera_25.png": "<base64>"}        | scenes, course             |
// | multipart | a file part per file, the part's name its path        | answers, title, format,    |
// |           | (.png parts are images, an .ipynb the notebook)       | course                     |
//
// format: pdf (default) or html. scenes: [{"name": "two_objects", "scene": {...}}], Blender-half
// scenes on built-in meshes, each rendered with its framing report. Each checkpoint found is
// graded and rendered by the workers.
#include <algorithm>
#include <atomic>

#include "core/base64.h"
#include "image/png_info.h"
#include "http/request_fields.h"
#include "http/route_context.h"
#include "sheet/assemble.h"
#include "sheet/sheet_html.h"
#include "sheet/sheet_pdf.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

constexpr size_t kMaxFiles = 16, kMaxPath = 200, kMaxTitle = 200, kMaxAnswers = 64 * 1024, kMaxScenes = 4;
// Three deliverables' saved frames and the Blender half's four renders, with room to spare.
constexpr size_t kMaxImages = 40, kMaxImageBytes = 16u << 20;
// What a sheet's images may decode to, summed from their headers before any decode: the course's
// 27 frames at 512 x 512 (7.1 M) and four hand-in renders at 3840 x 2160 (33.2 M) fit; 27 frames
// that each claim 4096 x 4096 (453 M, 1.8 GB as RGBA) do not.
constexpr std::uint64_t kMaxSheetPixels = 48u << 20;

// A path inside the student's folder: relative, no "..", no empty part.
bool safe_path(const std::string& path) {
  if (path.empty() || path.size() > kMaxPath || path.front() == '/') return false;
  for (size_t at = 0; at <= path.size();) {
    const size_t slash = std::min(path.find('/', at), path.size());
    const std::string part = path.substr(at, slash - at);
    if (part.empty() || part == "." || part == "..") return false;
    at = slash + 1;
  }
  return true;
}

Status add_image(sheet::SheetInput& input, const std::string& path, std::string bytes) {
  if (!safe_path(path))
    return make_error(ErrorCode::invalid_argument, "images: '" + path.substr(0, kMaxPath) + "' is not a path inside the submission");
  if (bytes.size() > kMaxImageBytes)
    return make_error(ErrorCode::payload_too_large, "images: '" + path + "' is over " + std::to_string(kMaxImageBytes) + " bytes");
  if (input.images.size() == kMaxImages) return make_error(ErrorCode::invalid_argument, "images: more than " + std::to_string(kMaxImages));
  input.images.push_back({path, std::move(bytes)});
  return Ok{};
}

// The student's notebook (HW2.ipynb): its answers are read, never run. Outputs make it large.
Status add_notebook(sheet::SheetInput& input, const std::string& path, const std::string& text) {
  if (text.size() > kMaxImageBytes) return make_error(ErrorCode::payload_too_large, "files: '" + path + "' is over " + std::to_string(kMaxImageBytes) + " bytes");
  if (!input.notebook.empty()) return make_error(ErrorCode::invalid_argument, "files: one notebook per submission; '" + path + "' is a second");
  input.notebook = text;
  return Ok{};
}

Status add_file(sheet::SheetInput& input, const std::string& path, const std::string& text, const Limits& limits) {
  if (path.ends_with(".png")) return add_image(input, path, text);
  if (path.ends_with(".ipynb") && safe_path(path)) return add_notebook(input, path, text);
  if (!safe_path(path))
    return make_error(ErrorCode::invalid_argument, "files: '" + path.substr(0, kMaxPath) + "' is not a path inside the submission");
  if (text.size() > limits.render.max_source_bytes)
    return make_error(ErrorCode::payload_too_large, "files: '" + path + "' is over " + std::to_string(limits.render.max_source_bytes) + " bytes");
  if (input.files.size() == kMaxFiles) return make_error(ErrorCode::invalid_argument, "files: more than " + std::to_string(kMaxFiles));
  input.files.push_back({path, text});
  return Ok{};
}

// Scenes on built-in meshes; parse_scene (in assemble) checks each, and its error is its section.
Status add_scenes(sheet::SheetInput& input, const RawRequest& raw) {
  if (!raw.fields.contains("scenes")) return Ok{};
  const json& scenes = raw.fields["scenes"];
  if (!scenes.is_array() || scenes.size() > kMaxScenes)
    return make_error(ErrorCode::invalid_argument, "scenes: expected an array of at most " + std::to_string(kMaxScenes) +
                                                       " {\"name\": ..., \"scene\": {...}}");
  for (size_t i = 0; i < scenes.size(); ++i) {
    const json& s = scenes[i];
    const std::string where = "scenes[" + std::to_string(i) + "]";
    if (!s.is_object() || !s.contains("scene") || !s["scene"].is_object())
      return make_error(ErrorCode::invalid_argument, where + ": expected {\"name\": ..., \"scene\": {...}}");
    const json name = s.value("name", json(where));
    if (!name.is_string() || name.get_ref<const std::string&>().size() > kMaxTitle)
      return make_error(ErrorCode::invalid_argument, where + ".name: expected a short string");
    input.scenes.push_back({name.get<std::string>(), s["scene"], {}});
  }
  return Ok{};
}

// The pixels every image of the sheet decodes to, from each PNG's header (a file that is no PNG is
// said so later, in its own section), refused as a whole before anything decodes one.
Status within_pixel_budget(const sheet::SheetInput& input) {
  std::uint64_t pixels = 0;
  for (const auto& image : input.images)
    if (const auto info = image::png_info(image.text)) pixels += std::uint64_t{info->width} * info->height;
  if (pixels <= kMaxSheetPixels) return Ok{};
  return make_error(ErrorCode::payload_too_large, "images: the PNGs' headers say they decode to " + std::to_string(pixels) +
                                                      " pixels in all; a sheet's limit is " + std::to_string(kMaxSheetPixels) +
                                                      " (27 frames at the course's canvas and four 4K renders fit)");
}

Expected<sheet::SheetInput> parse_sheet(const RawRequest& raw, const Limits& limits) {
  sheet::SheetInput input;
  auto title = text_field(raw.fields, "title", input.title, kMaxTitle);
  auto answers = text_field(raw.fields, "answers", "", kMaxAnswers);
  for (auto* f : {&title, &answers})
    if (!*f) return f->error();
  input.title = *title;
  input.answers = *answers;
  if (raw.fields.contains("files")) {
    const json& files = raw.fields["files"];
    if (!files.is_object()) return make_error(ErrorCode::invalid_argument, "files: expected an object of path -> source");
    for (const auto& [path, text] : files.items()) {
      if (!text.is_string()) return make_error(ErrorCode::invalid_argument, "files." + path + ": expected the file's text");
      if (auto s = add_file(input, path, text.get<std::string>(), limits); !s) return s.error();
    }
  }
  if (raw.fields.contains("images")) {
    const json& images = raw.fields["images"];
    if (!images.is_object()) return make_error(ErrorCode::invalid_argument, "images: expected an object of path -> base64 PNG");
    for (const auto& [path, data] : images.items()) {
      auto bytes = data.is_string() ? base64_decode(data.get<std::string>()) : std::nullopt;
      if (!bytes) return make_error(ErrorCode::invalid_argument, "images." + path + ": expected the file's bytes in base64");
      if (auto s = add_image(input, path, std::move(*bytes)); !s) return s.error();
    }
  }
  for (const auto& [name, file] : raw.files)
    if (auto s = add_file(input, name, file.content, limits); !s) return s.error();
  if (auto s = add_scenes(input, raw); !s) return s.error();
  if (auto s = within_pixel_budget(input); !s) return s.error();
  if (input.files.empty())
    return make_error(ErrorCode::invalid_argument, "files: send the student's shader files (e.g. shaders/starter_vert.js), each under its path");
  return input;
}

// A sheet decodes and lays out its images in this process (cairo), not in a worker: at most
// `limits.max_concurrent_sheets` at once, the rest told to come back.
class SheetSlot {
 public:
  explicit SheetSlot(size_t limit) : held_(in_flight_.fetch_add(1) < limit) {
    if (!held_) in_flight_.fetch_sub(1);
  }
  ~SheetSlot() {
    if (held_) in_flight_.fetch_sub(1);
  }
  SheetSlot(const SheetSlot&) = delete;
  SheetSlot& operator=(const SheetSlot&) = delete;
  bool held() const { return held_; }

 private:
  static inline std::atomic<size_t> in_flight_{0};
  bool held_;
};

void sheet(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  const SheetSlot slot(c.config.limits.max_concurrent_sheets);
  if (!slot.held())
    return send_problem(res, make_error(ErrorCode::queue_full, "the server is laying out " + std::to_string(c.config.limits.max_concurrent_sheets) +
                                                                   " sheets already; try again in a moment"),
                        req.path);
  auto raw = read_request(req);
  if (!raw) return send_problem(res, raw.error(), req.path);
  auto format = text_field(raw->fields, "format", "pdf", 8);
  if (!format) return send_problem(res, format.error(), req.path);
  if (*format != "pdf" && *format != "html")
    return send_problem(res, make_error(ErrorCode::invalid_argument, "format: pdf or html, not '" + *format + "'"), req.path);
  auto course = course_of(*raw, c.courses);
  if (!course) return send_problem(res, course.error(), req.path);
  auto input = parse_sheet(*raw, c.config.limits);
  if (!input) return send_problem(res, input.error(), req.path);
  input->viewer = viewer;
  auto assembled = sheet::assemble(c.pool, **course, std::move(*input), c.config.reference_places());
  if (!assembled) return send_problem(res, assembled.error(), req.path);
  if (*format == "html") return res.set_content(sheet::render_html(*assembled), "text/html; charset=utf-8");
  auto pdf = sheet::render_pdf(*assembled);
  if (!pdf) return send_problem(res, pdf.error(), req.path);
  res.set_header("Content-Disposition", "attachment; filename=\"sheet.pdf\"");
  res.set_content(std::move(*pdf), "application/pdf");
}

}  // namespace

void add_sheet_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/sheet", sheet);
}

}  // namespace shadelab::http
