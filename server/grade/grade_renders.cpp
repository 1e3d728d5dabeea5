#include "grade/grade_renders.h"

#include <algorithm>
#include <memory>

#include "image/encode.h"
#include "image/grid.h"
#include "image/metrics.h"

namespace shadelab::grade {

std::string heatmap_png(const SharedFrames& frames, const SharedFrames& reference, const render::RenderRequest& job, const GradeSpec& spec) {
  if (spec.picture == DifferencePicture::none) return {};
  std::vector<image::Image> heat;
  for (size_t k = 0; k < static_cast<size_t>(job.frames); ++k)
    heat.push_back(spec.picture == DifferencePicture::full ? image::heatmap(*frames[k], *reference[k])
                                                           : image::difference_blocks(*frames[k], *reference[k], kDifferenceBlockSide,
                                                                                      spec.options.compare));
  auto png = image::encode_png(image::compose_grid(image::GridLayout::for_frames(job.frames, job.width, job.height), heat));
  return png ? std::string(png->begin(), png->end()) : std::string();
}

Expected<SharedFrames> GradeRenders::frames_of(const render::RenderRequest& r, const scene::Mesh& m) {
  SharedFrames out;
  auto rendered = renderer_.render(r, m, [&](int, const image::Image& f, bool) { out.push_back(std::make_shared<const image::Image>(f)); });
  if (!rendered) return rendered.take_error();
  return out;
}

void GradeRenders::begin(const GradeSpec& spec) {
  work_ = {};
  store_.reset();
  if (spec.reference_store.empty()) return;
  const auto& info = renderer_.context_info();
  store_.emplace(spec.reference_store.folder, shared_store(spec.reference_store.shared), info.gl_renderer + " | " + info.gl_version);
}

store::SharedStore* GradeRenders::shared_store(const store::SharedStoreConfig& config) {
  if (config.url.empty()) return nullptr;
  if (!shared_ || shared_config_ != config) {
    auto opened = store::SharedStore::open(config);
    shared_ = opened ? std::move(*opened) : nullptr;  // an address that does not parse: no sharing
    shared_config_ = config;
  }
  return shared_.get();
}

const std::string& GradeRenders::mesh_address(const std::string& mesh_key, const scene::Mesh& mesh) {
  if (address_of_ != mesh_key) {
    address_ = scene::content_address(mesh);
    address_of_ = mesh_key;
  }
  return address_;
}

Expected<SharedFrames> GradeRenders::stored_or_rendered(const render::RenderRequest& r, const scene::Mesh& m, const std::string& mesh_key) {
  const std::string stored = store_ ? store_->key(r, mesh_address(mesh_key, m)) : std::string();
  if (store_)
    if (auto loaded = store_->load(stored, r)) {
      ++work_.from_store;
      return std::move(*loaded);
    }
  auto frames = frames_of(r, m);
  if (!frames) return frames;
  ++work_.rendered;
  if (store_) store_->save(stored, *frames);
  return frames;
}

Expected<SharedFrames> GradeRenders::cached_frames(const render::RenderRequest& r, const scene::Mesh& m, const std::string& mesh_key) {
  std::string key = render::pixel_identity(r) + '\0' + mesh_key;
  if (const SharedFrames* hit = references_.find(key)) {
    ++work_.from_memory;
    return *hit;
  }
  auto frames = stored_or_rendered(r, m, mesh_key);
  if (frames) references_.insert(std::move(key), *frames);
  return frames;
}

std::vector<RenderedMistake> GradeRenders::rendered_mistakes(const GradeSpec& spec, const std::vector<const Mistake*>& which,
                                                             const render::RenderRequest& reference, const scene::Mesh& mesh,
                                                             const std::string& mesh_key) {
  std::vector<RenderedMistake> mistakes;
  for (const Mistake* mk : which) {
    render::RenderRequest mr = reference;
    mr.vertex = mk->vertex;
    mr.fragment = mk->fragment;
    if (auto frames = cached_under_lights(spec, mr, mesh, mesh_key)) mistakes.push_back({mk->id, mk->message, std::move(*frames)});
  }
  return mistakes;
}

// `base` under the probe's light, for the names the program declares as the page does; a name
// declared otherwise stays as the homework sets it, as in the browser.
Expected<render::RenderRequest> GradeRenders::with_light(const GradeSpec& spec, const render::RenderRequest& base, const Probe& probe) {
  auto program = renderer_.compile(base.vertex, base.fragment);
  if (!program) return program.take_error();
  render::RenderRequest lit = base;
  for (auto& s : probe_settings(spec, probe)) {
    const bool declared = std::any_of(program->uniforms.begin(), program->uniforms.end(),
                                      [&](const auto& u) { return u.name == s.name && u.type == s.type && u.array_size == 1; });
    const bool set = std::any_of(lit.uniforms.begin(), lit.uniforms.end(), [&](const auto& u) { return u.name == s.name; });
    if (declared && !set) lit.uniforms.push_back({s.name, std::move(s.value)});
  }
  return lit;
}

const std::vector<model::FrameSurface>* GradeRenders::surfaces(const FormulaSpec& formula, const render::RenderRequest& reference,
                                                              const scene::Mesh& mesh, const std::string& mesh_key, GeometryKept kept,
                                                              SampleGeometry samples) {
  auto requests = geometry_requests(formula, reference, samples);
  if (!requests) return nullptr;
  const auto key_of = [&](auto begin, auto end) {
    std::string key = mesh_key;
    for (auto g = begin; g != end; ++g) key += '\0' + render::pixel_identity(g->request);
    return key;
  };
  std::string key = key_of(requests->begin(), requests->end());
  if (auto* hit = surfaces_.find(key)) {
    ++work_.from_memory;
    return hit;
  }
  // A render at a time, each turned into the object's pixels before the next: the float frames
  // are ten times the surfaces' size. The samples start from the averaged geometry where this
  // worker holds it (the grade that asks for them has just read it).
  std::vector<model::FrameSurface> out;
  auto first = std::find_if(requests->begin(), requests->end(), [](const GeometryRender& g) { return g.quantity == model::Quantity::sample_flat_normal; });
  if (const auto* averaged = first != requests->end() ? surfaces_.find(key_of(requests->begin(), first)) : nullptr)
    out = *averaged;
  else
    first = requests->begin();
  for (auto it = first; it != requests->end(); ++it) {
    const auto& [request, quantity, sample] = *it;
    auto frames = kept == GeometryKept::with_references ? stored_or_rendered(request, mesh, mesh_key) : frames_of(request, mesh);
    if (!frames) return nullptr;
    if (kept == GeometryKept::in_memory) ++work_.rendered;
    for (std::size_t k = 0; k < frames->size(); ++k) {
      if (quantity == model::Quantity::position) out.push_back(model::surface_from(*(*frames)[k]));
      else if (k < out.size()) model::add_quantity(out[k], *(*frames)[k], quantity, sample);
    }
  }
  std::size_t bytes = 0;
  for (const auto& s : out) bytes += s.bytes();
  return &surfaces_.insert(std::move(key), std::move(out), bytes);
}

std::function<const std::vector<model::FrameSurface>*()> GradeRenders::sampled_surfaces(const FormulaSpec& formula,
                                                                                      const render::RenderRequest& reference,
                                                                                      const scene::Mesh& mesh, const std::string& mesh_key,
                                                                                      GeometryKept kept) {
  if (!has_sample_geometry(formula, reference)) return {};
  return [this, &formula, reference, &mesh, mesh_key, kept] { return surfaces(formula, reference, mesh, mesh_key, kept, SampleGeometry::each_sample); };
}

// `base` under the homework's light, then under each probe light.
Expected<std::vector<render::RenderRequest>> GradeRenders::under_lights(const GradeSpec& spec, const render::RenderRequest& base) {
  std::vector<render::RenderRequest> lit = {base};
  for (const auto& probe : spec.probes) {
    auto moved = with_light(spec, base, probe);
    if (!moved) return moved.take_error();
    lit.push_back(std::move(*moved));
  }
  return lit;
}

// A reference's or a mistake's frames, under the homework's light and then each probe light,
// light by light through the caches.
Expected<SharedFrames> GradeRenders::cached_under_lights(const GradeSpec& spec, const render::RenderRequest& base,
                                                         const scene::Mesh& mesh, const std::string& cache_key) {
  auto lit = under_lights(spec, base);
  if (!lit) return lit.take_error();
  SharedFrames all;
  for (const auto& r : *lit) {
    auto frames = cached_frames(r, mesh, cache_key);
    if (!frames) return frames.take_error();
    all.insert(all.end(), frames->begin(), frames->end());
  }
  return all;
}

// The submission under every light, drawn together (Renderer::render_together), with the census
// of its colours: the NaN and infinities the canvas would store as 0 or clamp.
Expected<GradeRenders::SubmissionFrames> GradeRenders::submission_under_lights(const GradeSpec& spec,
                                                                               const render::RenderRequest& base,
                                                                               const scene::Mesh& mesh) {
  auto lit = under_lights(spec, base);
  if (!lit) return lit.take_error();
  std::vector<SharedFrames> frames(lit->size());
  std::vector<std::vector<image::NonFinite>> counts(lit->size());
  auto rendered = renderer_.render_together(
      *lit, mesh, [&](int i, int, const image::Image& f, bool) { frames[static_cast<size_t>(i)].push_back(std::make_shared<const image::Image>(f)); },
      [&](int i, int, const image::NonFinite& n) { counts[static_cast<size_t>(i)].push_back(n); });
  if (!rendered) return rendered.take_error();
  SubmissionFrames out;
  for (size_t i = 0; i < lit->size(); ++i) {
    out.frames.insert(out.frames.end(), frames[i].begin(), frames[i].end());
    out.non_finite.insert(out.non_finite.end(), counts[i].begin(), counts[i].end());
  }
  return out;
}

MovedFlatColour GradeRenders::moved_flat_colour(const FormulaSpec& formula, const render::RenderRequest& at, const scene::Mesh& mesh) {
  auto requests = geometry_requests(formula, at);
  if (!requests) return {};
  const auto flat = std::find_if(requests->begin(), requests->end(), [](const GeometryRender& g) { return g.quantity == model::Quantity::flat_colour; });
  if (flat == requests->end()) return {};
  return [this, request = flat->request, &mesh](const std::vector<std::size_t>& angle, const std::vector<double>& offset) -> Expected<SharedFrames> {
    render::RenderRequest moved = request;
    moved.angles.clear();
    for (std::size_t i = 0; i < angle.size() && i < offset.size(); ++i)
      if (angle[i] < request.angles.size()) moved.angles.push_back(request.angles[angle[i]] + offset[i]);
    moved.frames = static_cast<int>(moved.angles.size());
    auto frames = frames_of(moved, mesh);
    if (frames) ++work_.rendered;
    return frames;
  };
}

Expected<SharedFrames> GradeRenders::at_angles(render::RenderRequest request, const scene::Mesh& mesh, const std::vector<double>& angles) {
  request.angles = angles;
  request.frames = static_cast<int>(angles.size());
  request.pixel_type = image::PixelType::u8;
  auto frames = frames_of(request, mesh);
  if (frames) ++work_.rendered;
  return frames;
}

}  // namespace shadelab::grade
