#include "sheet/sheet_pdf.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>

#include "sheet/cairo_png.h"

namespace shadelab::sheet {

namespace {

constexpr double kPageWidth = 595.276, kPageHeight = 841.89;  // A4 in points
constexpr double kMargin = 42;
constexpr double kWidth = kPageWidth - 2 * kMargin;
constexpr char kSans[] = "DejaVu Sans", kMono[] = "DejaVu Sans Mono";

struct Colour {
  double r, g, b;
};
constexpr Colour kInk{0.1, 0.1, 0.1}, kGrey{0.45, 0.45, 0.45}, kPass{0.05, 0.45, 0.15}, kFail{0.7, 0.1, 0.1},
    kMarked{1.0, 0.93, 0.6};

// An image wider than `width` pixels halved until it is not (box filter: every source pixel
// counts): a 1920-pixel grid drawn 7 inches wide needs no more than ~137 dpi, and embedding it
// whole made each grid page 1.2 MB. Takes ownership of `img`.
constexpr int kMaxImageWidth = 1000;
cairo_surface_t* at_most(cairo_surface_t* img, int width) {
  while (cairo_image_surface_get_width(img) > width) {
    const int w = cairo_image_surface_get_width(img) / 2, h = std::max(1, cairo_image_surface_get_height(img) / 2);
    cairo_surface_t* half = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
    cairo_t* cr = cairo_create(half);
    cairo_scale(cr, 0.5, 0.5);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
    cairo_paint(cr);
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    img = half;
  }
  return img;
}

// Writes down the page, starting a new one when the next item does not fit.
class PageWriter {
 public:
  explicit PageWriter(cairo_t* cr) : cr_(cr) {}

  void room_for(double height) {
    if (y_ + height <= kPageHeight - kMargin) return;
    new_page();
  }
  void new_page() {
    footer();
    cairo_show_page(cr_);
    ++page_;
    y_ = kMargin;
  }
  void gap(double points) { y_ += points; }

  void text(const std::string& s, const char* face, double size, Colour c, bool bold = false) {
    font(face, size, bold);
    room_for(size * 1.35);
    draw(s, kMargin, y_ + size, c);
    y_ += size * 1.35;
  }

  // Proportional text wrapped at word boundaries; paragraphs at newlines.
  void paragraph(const std::string& s, double size, Colour c) {
    font(kSans, size, false);
    std::istringstream lines(s);
    for (std::string line; std::getline(lines, line);) {
      std::string current;
      std::istringstream words(line);
      for (std::string word; words >> word;) {
        const std::string candidate = current.empty() ? word : current + " " + word;
        if (!current.empty() && advance(candidate) > kWidth) {
          text(current, kSans, size, c);
          current = word;
        } else {
          current = candidate;
        }
      }
      text(current, kSans, size, c);
    }
  }

  // The PNG at the page's width (or `width` points); `boxes` (in the image's pixels) stroked over it, each labelled.
  void image(const std::string& png, const std::vector<scene_render::ObjectFraming>& boxes = {},
             const char* missing = "(no image: it did not render)", double width = kWidth) {
    Surface decoded = decode_png(png);
    if (!decoded) {
      text(missing, kSans, 9, kGrey);
      return;
    }
    const double scale = width / cairo_image_surface_get_width(decoded.get());
    const double height = cairo_image_surface_get_height(decoded.get()) * scale;
    room_for(height);
    paint(std::move(decoded), kMargin, width);
    framing_boxes(boxes, scale, height);
    y_ += height;
  }

  // A decoded PNG drawn at (x, y_), `width` points wide.
  void paint(Surface decoded, double x, double width) {
    if (!decoded) return;
    cairo_surface_t* img = at_most(decoded.release(), kMaxImageWidth);
    const double scale = width / cairo_image_surface_get_width(img);
    cairo_save(cr_);
    cairo_translate(cr_, x, y_);
    cairo_scale(cr_, scale, scale);
    cairo_set_source_surface(cr_, img, 0, 0);
    cairo_paint(cr_);
    cairo_restore(cr_);
    cairo_surface_destroy(img);
  }

  // Two PNGs side by side, each at half the page's width (less a gutter), captioned above.
  void image_pair(const std::string& left, const std::string& left_caption, const std::string& right, const std::string& right_caption) {
    constexpr double kGutter = 12;
    const double half = (kWidth - kGutter) / 2;
    Surface a = decode_png(left), b = decode_png(right);
    const auto height_of = [&](const Surface& s) {
      return s ? cairo_image_surface_get_height(s.get()) * half / cairo_image_surface_get_width(s.get()) : 0.0;
    };
    const double height = std::max(height_of(a), height_of(b));
    font(kSans, 8.5, false);
    room_for(height + 8.5 * 1.35);
    draw(left_caption, kMargin, y_ + 8.5, kGrey);
    draw(right_caption, kMargin + half + kGutter, y_ + 8.5, kGrey);
    y_ += 8.5 * 1.35;
    paint(std::move(a), kMargin, half);
    paint(std::move(b), kMargin + half + kGutter, half);
    y_ += height;
  }

  // Monospaced code with line numbers, wrapped to the width; marked lines on a yellow band.
  void code(const CodeListing& listing) {
    constexpr double kSize = 7, kLine = 8.6;
    text(listing.file_name, kMono, 8.5, kInk, true);
    font(kMono, kSize, false);
    const double gutter = advance("0000 ");
    const size_t columns = static_cast<size_t>(std::max(20.0, (kWidth - gutter) / advance("M")));
    std::istringstream lines(printable(listing.text));
    int number = 0;
    for (std::string line; std::getline(lines, line);) {
      const bool marked = listing.marked_lines.count(++number) > 0;
      size_t at = 0;
      do {
        room_for(kLine);
        font(kMono, kSize, false);
        if (marked) {
          cairo_set_source_rgb(cr_, kMarked.r, kMarked.g, kMarked.b);
          cairo_rectangle(cr_, kMargin, y_, kWidth, kLine);
          cairo_fill(cr_);
        }
        if (at == 0) {
          const std::string n = std::to_string(number);
          draw(n, kMargin + gutter - advance(n + " "), y_ + kSize, marked ? kFail : kGrey);
        }
        draw(utf8_prefix(line, at, columns), kMargin + gutter, y_ + kSize, kInk);
        y_ += kLine;
      } while (at < line.size());
    }
  }

  void finish() { footer(); }

 private:
  // Each object's box over the image (clipped to it): green when fully in frame, red when not.
  void framing_boxes(const std::vector<scene_render::ObjectFraming>& boxes, double scale, double height) {
    cairo_save(cr_);
    cairo_rectangle(cr_, kMargin, y_, kWidth, height);
    cairo_clip(cr_);
    font(kSans, 7.5, true);
    for (const auto& f : boxes) {
      if (!f.box) continue;
      const Colour c = f.fully_visible ? kPass : kFail;
      const double x0 = kMargin + f.box->min.x * scale, y0 = y_ + f.box->min.y * scale;
      cairo_set_source_rgb(cr_, c.r, c.g, c.b);
      cairo_set_line_width(cr_, 1.2);
      cairo_rectangle(cr_, x0, y0, (f.box->max.x - f.box->min.x) * scale, (f.box->max.y - f.box->min.y) * scale);
      cairo_stroke(cr_);
      draw(f.name, std::max(x0, kMargin) + 2, std::max(y0, y_) + 9, c);
    }
    cairo_restore(cr_);
  }

 public:
 private:
  void font(const char* face, double size, bool bold) {
    cairo_select_font_face(cr_, face, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }
  double advance(const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr_, s.c_str(), &e);
    return e.x_advance;
  }
  void draw(const std::string& s, double x, double baseline, Colour c) {
    cairo_set_source_rgb(cr_, c.r, c.g, c.b);
    cairo_move_to(cr_, x, baseline);
    cairo_show_text(cr_, s.c_str());
  }
  // Up to `columns` characters of `line` from byte `at` (advanced past them), whole UTF-8 sequences.
  static std::string utf8_prefix(const std::string& line, size_t& at, size_t columns) {
    const size_t start = at;
    for (size_t n = 0; at < line.size() && n < columns; ++n) {
      ++at;
      while (at < line.size() && (static_cast<unsigned char>(line[at]) & 0xc0) == 0x80) ++at;
    }
    return line.substr(start, at - start);
  }
  void footer() {
    font(kSans, 7.5, false);
    draw(std::to_string(page_), kPageWidth / 2, kPageHeight - kMargin / 2, kGrey);
  }

  cairo_t* cr_;
  double y_ = kMargin;
  int page_ = 1;
};

void checkpoint(PageWriter& w, const CheckpointSection& s, size_t index) {
  w.text(std::to_string(index) + ". " + s.title, kSans, 13, kInk, true);
  // Wrapped: a verdict with the lags found runs past the page's width, and a TA reads all of it.
  const std::string_view how = section_class(s);
  w.paragraph(section_verdict(s), 9.5, how == "pass" ? kPass : how == "fail" ? kFail : kGrey);
  // Below the score: the code's report when it was graded, else what was handed in.
  for (size_t k = 0; k < s.report.messages.size() && k < 4; ++k) w.paragraph(s.report.messages[k], 8.5, kGrey);
  for (const auto& line : frames_lines(s)) w.paragraph(line, 9, s.frames_report && s.frames_report->pass ? kPass : kFail);
  w.gap(4);
  if (!s.saved_grid_png.empty() && !s.grid_png.empty()) {
    w.image_pair(s.saved_grid_png, "the frames the student saved", s.grid_png, s.grid_caption);
  } else {
    if (!s.grid_caption.empty()) w.text(s.grid_caption, kSans, 8.5, kGrey);
    w.image(s.grid_png, {}, s.graded ? "(no image: it did not render)" : "(no grid)");
  }
  w.gap(10);
  for (const auto& listing : s.code) {
    w.code(listing);
    w.gap(8);
  }
}

void scene(PageWriter& w, const SceneSection& s) {
  char lens[64];
  std::snprintf(lens, sizeof lens, " (lens %g mm, %d x %d)", s.lens_mm, s.width, s.height);
  w.text("Blender: " + printable(s.name) + (s.error.empty() ? lens : ""), kSans, 13, kInk, true);
  if (!s.error.empty()) {
    w.paragraph("does not render: " + printable(s.error), 9.5, kFail);
    return;
  }
  const std::string verdict = framing_verdict(s);
  const bool all_in = std::all_of(s.framing.begin(), s.framing.end(), [](const auto& f) { return f.fully_visible || !f.drawn; });
  w.text(verdict, kSans, 9.5, all_in && !s.framing.empty() ? kPass : kFail);
  w.gap(4);
  w.image(s.png, s.framing);
  w.gap(6);
  for (const auto& f : s.framing) w.text(framing_line(f), kSans, 8.5, kInk);
  for (const auto& [name, material] : s.materials) w.paragraph(printable(name) + ": " + material_line(material), 8.5, kGrey);
}

// Each question with the answer under it in the student's notebook, the colours it gives rendered.
void answered(PageWriter& w, const Sheet& sheet) {
  if (!sheet.notebook_note.empty()) w.paragraph(printable(sheet.notebook_note), 8.5, kGrey);
  for (size_t i = 0; i < sheet.answered.size(); ++i) {
    const AnswerSection& a = sheet.answered[i];
    w.paragraph(std::to_string(i + 1) + ". " + printable(a.question), 9.5, kGrey);
    w.gap(2);
    w.paragraph(a.answer.empty() ? printable(a.missing) : printable(a.answer), 10, a.answer.empty() ? kGrey : kInk);
    if (!a.render_caption.empty()) w.paragraph(printable(a.render_caption), 8.5, kGrey);
    if (!a.render_png.empty()) w.image(a.render_png, {}, "(no image: it did not render)", kWidth / 2);
    w.gap(8);
  }
}

// The notebook's questions, then the student's answers: from their notebook, else as written in an answers file.
void questions(PageWriter& w, const Sheet& sheet) {
  w.text("Questions", kSans, 13, kInk, true);
  w.gap(4);
  if (!sheet.answered.empty()) return answered(w, sheet);
  if (!sheet.notebook_problem.empty()) w.paragraph(sheet.notebook_name + ": " + printable(sheet.notebook_problem), 9.5, kFail);
  for (size_t i = 0; i < sheet.questions.size(); ++i) w.paragraph(std::to_string(i + 1) + ". " + printable(sheet.questions[i]), 9.5, kGrey);
  w.gap(6);
  w.text("Answers", kSans, 11, kInk, true);
  w.gap(2);
  w.paragraph(sheet.answers.empty() ? "(no answers given)" : printable(sheet.answers), 10, sheet.answers.empty() ? kGrey : kInk);
}

void handed_in(PageWriter& w, const ImageSection& s) {
  w.text(printable(s.title) + " (" + printable(s.file) + ")", kSans, 13, kInk, true);
  if (s.check && s.problem.empty()) w.paragraph(printable(image_verdict(*s.check)), 9.5, s.check->verdict.pass ? kPass : kFail);
  if (!s.problem.empty()) {
    w.text(printable(s.problem), kSans, 9.5, kFail);
    return;
  }
  w.gap(4);
  w.image(s.png, {}, "(no image: it cannot be read)");
}

// The notebook's order: a page per deliverable, the questions and answers, a page per hand-in
// image, then a page per scene ShadeLab rendered.
void draw_sheet(PageWriter& w, const Sheet& sheet) {
  w.text(printable(sheet.title), kSans, 18, kInk, true);
  w.gap(6);
  for (size_t i = 0; i < sheet.checkpoints.size(); ++i) {
    if (i > 0) w.new_page();
    checkpoint(w, sheet.checkpoints[i], i + 1);
  }
  if (!sheet.questions.empty() || !sheet.answers.empty()) {
    w.new_page();
    questions(w, sheet);
  }
  for (const auto& s : sheet.images) {
    w.new_page();
    handed_in(w, s);
  }
  for (const auto& s : sheet.scenes) {
    w.new_page();
    scene(w, s);
  }
}

}  // namespace

Expected<std::string> render_pdf(const Sheet& sheet) {
  std::string out;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_pdf_surface_create_for_stream(append_to_string, &out, kPageWidth, kPageHeight), cairo_surface_destroy);
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, printable(sheet.title).c_str());
  // A fixed date: the same sheet is the same bytes (cairo would write the current time).
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "2000-01-01T00:00:00Z");
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
  PageWriter w(cr.get());
  draw_sheet(w, sheet);
  w.finish();
  cairo_show_page(cr.get());
  cr.reset();
  cairo_surface_finish(surface.get());
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    return make_error(ErrorCode::io_error, std::string("cairo could not write the PDF: ") +
                                               cairo_status_to_string(cairo_surface_status(surface.get())));
  return out;
}

}  // namespace shadelab::sheet
