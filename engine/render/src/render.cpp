#include "ncpost/render/render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ncpost/canon/cycle.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::render {
namespace {

constexpr std::size_t kMaxLimitReports = 100;

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

// Collects the calls of a cycle expansion.
class Collect final : public canon::Sink {
 public:
  void call(const canon::Call& call) override { calls.push_back(call); }
  std::vector<canon::Call> calls;
};

}  // namespace

// The XML form's events, built straight into the input tree, with the size the same XML would
// have as text (RenderOptions::batch_bytes is measured in it).
class Renderer::TreeEvents final : public canon::XmlEvents {
 public:
  explicit TreeEvents(xslt::InputTree& tree) : tree_(tree) {}
  void start_element(std::string_view name) override {
    tree_.start_element(name);
    text_bytes_ += name.size() + 1;
  }
  void attribute(std::string_view name, std::string_view value) override {
    tree_.attribute(name, value);
    text_bytes_ += name.size() + value.size() + 4;
  }
  void text(std::string_view characters) override {
    tree_.text(characters);
    text_bytes_ += characters.size() + 1;
  }
  void end_element(std::string_view name) override {
    tree_.end_element();
    text_bytes_ += name.size() + 3;
  }
  void clear() {
    tree_.clear();
    text_bytes_ = 0;
  }
  [[nodiscard]] std::size_t text_bytes() const noexcept { return text_bytes_; }

 private:
  xslt::InputTree& tree_;
  std::size_t text_bytes_ = 0;
};

// Takes the motions the profile wants as runs (render.motion_runs) out of the XML, with the
// values their elements would carry: -0 as 0, as the XML form writes it.
class Renderer::RunTaker final : public canon::MotionRuns {
 public:
  RunTaker(const profile::Profile::MotionRuns& kinds, std::vector<xslt::RunMotion>& motions)
      : kinds_(kinds), motions_(motions) {}

  std::optional<std::size_t> take(const canon::Call& call) override {
    xslt::RunMotion m;
    const canon::Pose* end = nullptr;
    if (const auto* t = std::get_if<canon::StraightTraverse>(&call); t && kinds_.traverse) {
      m.kind = xslt::RunMotion::Kind::Traverse;
      end = &t->to;
    } else if (const auto* f = std::get_if<canon::StraightFeed>(&call); f && kinds_.feed) {
      m.kind = xslt::RunMotion::Kind::Feed;
      end = &f->to;
    } else if (const auto* a = std::get_if<canon::ArcFeed>(&call); a && kinds_.arc) {
      const std::optional<canon::PlaneArc> p = canon::plane_arc(*a);
      if (!p) return std::nullopt;  // a tilted arc stays an element (its template says why)
      m.kind = xslt::RunMotion::Kind::Arc;
      end = &a->end;
      m.cx = plain(a->centre.x), m.cy = plain(a->centre.y), m.cz = plain(a->centre.z);
      m.plane = p->plane == canon::Plane::Yz   ? xslt::RunMotion::Plane::Yz
                : p->plane == canon::Plane::Xz ? xslt::RunMotion::Plane::Xz
                                               : xslt::RunMotion::Plane::Xy;
      m.rotation = p->rotation;
    } else {
      return std::nullopt;
    }
    m.x = plain(end->x), m.y = plain(end->y), m.z = plain(end->z);
    if (end->rotary) {
      m.has_rotary = true;
      m.a = plain(end->rotary->a), m.b = plain(end->rotary->b), m.c = plain(end->rotary->c);
    }
    motions_.push_back(m);
    return motions_.size() - 1;
  }

 private:
  static double plain(double v) { return v == 0 ? 0.0 : v; }
  const profile::Profile::MotionRuns& kinds_;
  std::vector<xslt::RunMotion>& motions_;
};

class Renderer::ChunkRenderer final : public canon::ChunkSink {
 public:
  explicit ChunkRenderer(Renderer& owner) : owner_(owner) {}
  void chunk(const canon::ChunkView& chunk) override { owner_.render_chunk(chunk); }

 private:
  Renderer& owner_;
};

Renderer::Renderer(const profile::LoadedProfile& profile, TextSink out, RenderOptions options,
                   std::string input_name)
    : profile_(profile),
      out_(std::move(out)),
      input_name_(std::move(input_name)),
      job_(profile::job_config(profile.profile)),
      params_{{"program_number", std::to_string(profile.profile.program_number)},
              {"profile_id", profile.profile.id},
              {"arcs", profile.profile.arcs == profile::Arcs::R ? "r" : "ijk"},
              {"tool", "0"}},
      tree_events_(std::make_unique<TreeEvents>(tree_)),
      run_taker_(profile.profile.motion_runs.any()
                     ? std::make_unique<RunTaker>(profile.profile.motion_runs, run_motions_)
                     : nullptr),
      chunk_sink_(std::make_unique<ChunkRenderer>(*this)),
      chunker_(std::make_unique<canon::Chunker>(*chunk_sink_, options.chunk)),
      single_chunk_(options.single_chunk),
      batch_bytes_(options.batch_bytes),
      batch_delay_(options.batch_delay) {
  job_.set_cancel(options.cancel);
  if (const auto& machine = profile.profile.kinematics) {
    kinematics_ = std::make_unique<KinematicsConverter>(
        *machine, profile.profile.units == xslt::Units::Inch ? 25.4 : 1.0);
    max_kinematics_warnings_ = options.max_kinematics_warnings;
    // For the stylesheet: whether the control keeps the tool tip (TCP words), and the rotary
    // addresses the motions carry (docs/kinematics.md, "Stylesheets").
    std::string axes{machine->primary.name, machine->secondary.name};
    std::sort(axes.begin(), axes.end());
    params_.emplace_back("tcp", machine->tool_centre_point ? "yes" : "no");
    params_.emplace_back("rotary_axes", axes);
  }
}

Renderer::~Renderer() = default;

void Renderer::report(diag::Code code, diag::Severity severity, std::string message) {
  auto d = diag::make(code, 0, 0, std::move(message));
  d.severity = severity;
  if (severity == diag::Severity::Error && !failed_ && !in_batch_) {
    // The chunks gathered so far were complete before the error: without batching they would
    // have been rendered already, so they are now, and the output ends where it did.
    render_batch();
  }
  if (severity == diag::Severity::Error) failed_ = true;
  diagnostics_.push_back({input_name_, std::move(d)});
}

std::string Renderer::where(const canon::Call& call) const {
  std::string s;
  if (workingstep_)
    s = "workingstep #" + std::to_string(workingstep_->id) + " \"" + workingstep_->name + "\"";
  else
    s = "outside any workingstep";
  return s + ", " + canon::format_call(call);
}

void Renderer::check_point(double x, double y, double z, const canon::Call& call) {
  const auto& lim = profile_.profile.limits;
  if (!lim.x && !lim.y && !lim.z) return;
  // Machine coordinates in the controller's unit: setup transform of the point in mm.
  const double to_ctl = unit_mm_ / (profile_.profile.units == xslt::Units::Inch ? 25.4 : 1.0);
  const auto& m = profile_.profile.setup.matrix;
  const auto& t = profile_.profile.setup.translation;
  const std::array<double, 3> p{x * to_ctl, y * to_ctl, z * to_ctl};
  const char* names = "XYZ";
  const std::optional<profile::Range>* ranges[3] = {&lim.x, &lim.y, &lim.z};
  for (int a = 0; a < 3; ++a) {
    if (!*ranges[a]) continue;
    const auto r = static_cast<std::size_t>(a) * 3;
    const double v =
        m[r] * p[0] + m[r + 1] * p[1] + m[r + 2] * p[2] + t[static_cast<std::size_t>(a)];
    const auto& range = **ranges[a];
    if (v < range.min - 1e-9 || v > range.max + 1e-9)
      report(diag::Code::RenderLimit, lim.severity,
             std::string("travel ") + names[a] + number(v) + " outside " + number(range.min) +
                 ".." + number(range.max) + " (" + where(call) + ")");
  }
}

void Renderer::check_limits(const canon::Call& call) {
  if (limit_reports_ >= kMaxLimitReports) return;
  const std::size_t before = diagnostics_.size();
  const auto& lim = profile_.profile.limits;
  const double feed_to_ctl = unit_mm_ / (profile_.profile.units == xslt::Units::Inch ? 25.4 : 1.0);
  auto feed = [&](double rate) {
    if (lim.max_feed && rate * feed_to_ctl > *lim.max_feed + 1e-9)
      report(diag::Code::RenderLimit, lim.severity,
             "feed " + number(rate * feed_to_ctl) + " above the maximum " + number(*lim.max_feed) +
                 " (" + where(call) + ")");
  };
  auto tool = [&](std::int64_t slot) {
    if (lim.tool_number && slot != 0 &&
        (slot < (*lim.tool_number)[0] || slot > (*lim.tool_number)[1]))
      report(diag::Code::RenderLimit, lim.severity,
             "tool number " + std::to_string(slot) + " outside " +
                 std::to_string((*lim.tool_number)[0]) + ".." +
                 std::to_string((*lim.tool_number)[1]) + " (" + where(call) + ")");
  };
  std::visit(
      [&](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, canon::StraightTraverse> ||
                      std::is_same_v<T, canon::StraightFeed>) {
          check_point(c.to.x, c.to.y, c.to.z, call);
        } else if constexpr (std::is_same_v<T, canon::ArcFeed>) {
          check_point(c.end.x, c.end.y, c.end.z, call);
        } else if constexpr (std::is_same_v<T, canon::NurbsFeed>) {
          if (!c.points.empty())
            check_point(c.points.back().x, c.points.back().y, c.points.back().z, call);
        } else if constexpr (std::is_same_v<T, canon::Cycle>) {
          check_point(c.x, c.y, c.safe_z, call);
          check_point(c.x, c.y, c.bottom_z, call);
          feed(c.feed);
        } else if constexpr (std::is_same_v<T, canon::SetFeedRate>) {
          feed(c.rate);
        } else if constexpr (std::is_same_v<T, canon::SetSpindleSpeed>) {
          if (lim.max_spindle && c.rpm > *lim.max_spindle + 1e-9)
            report(diag::Code::RenderLimit, lim.severity,
                   "spindle speed " + number(c.rpm) + " above the maximum " +
                       number(*lim.max_spindle) + " (" + where(call) + ")");
        } else if constexpr (std::is_same_v<T, canon::SelectTool> ||
                             std::is_same_v<T, canon::ChangeTool>) {
          tool(c.slot);
        }
      },
      call);
  limit_reports_ += diagnostics_.size() - before;
}

// The workingstep's output options that the profile cannot honour are taken off its Begin
// (so that no stylesheet acts on half of them), each kind reported once per job (RENDER-011).
std::optional<canon::Call> Renderer::honoured_options(const canon::Begin& b) {
  if (b.scope != canon::Scope::Workingstep || b.options.empty()) return std::nullopt;
  canon::Begin honoured = b;
  for (const auto& entry : canon::kOutputOptions) {
    const canon::Switch s = b.options.get(entry.option);
    if (s == canon::Switch::Unset || profile_.profile.honours(entry.option)) continue;
    honoured.options.set(entry.option, canon::Switch::Unset);
    const auto bit = static_cast<std::uint8_t>(1U << static_cast<unsigned>(entry.option));
    if ((options_reported_ & bit) != 0) continue;
    options_reported_ |= bit;
    report(diag::Code::RenderOutputOption, diag::Severity::Warning,
           "workingstep #" + std::to_string(b.entity.id) + " '" + b.entity.name + "' asks for " +
               std::string(entry.name) + "=" + std::string(canon::switch_name(s)) +
               ", which profile '" + profile_.profile.id +
               "' cannot write (capabilities.output_options); written without it (reported once "
               "per job)");
  }
  if (honoured.options == b.options) return std::nullopt;
  return canon::Call{std::move(honoured)};
}

void Renderer::call(const canon::Call& incoming) {
  if (finished_) return;
  std::optional<canon::Call> replaced;
  if (const auto* b = std::get_if<canon::Begin>(&incoming)) replaced = honoured_options(*b);
  const canon::Call& call = replaced ? *replaced : incoming;
  if (const auto* b = std::get_if<canon::Begin>(&call); b && b->scope == canon::Scope::Workingstep)
    workingstep_ = b->entity;
  if (const auto* u = std::get_if<canon::UseLengthUnits>(&call))
    unit_mm_ = u->units == canon::Units::Inches        ? 25.4
               : u->units == canon::Units::Centimetres ? 10.0
                                                       : 1.0;
  // With kinematics the limits apply to the machine's positions: forward() checks them.
  if (!kinematics_) check_limits(call);
  const auto& caps = profile_.profile;
  if (const auto* cycle = std::get_if<canon::Cycle>(&call); cycle) {
    if (const auto e = canon::check(*cycle); e != canon::CycleError::None) {
      report(diag::Code::RenderCycle, diag::Severity::Error,
             std::string(canon::describe(e)) + " (" + where(call) + ")");
      return;
    }
    if (caps.canned_cycles == profile::CannedCycles::Expand) {
      Collect expansion;
      (void)canon::expand_cycle(*cycle, expansion);
      for (const auto& c : expansion.calls) forward(c);
      return;
    }
  }
  if (const auto* nurbs = std::get_if<canon::NurbsFeed>(&call);
      nurbs && caps.nurbs == profile::NurbsMode::Linearize) {
    const auto points = linearize(*nurbs, caps.chord_tolerance);
    if (points.empty()) {
      report(diag::Code::RenderNurbs, diag::Severity::Error,
             "invalid NURBS, or one that cannot be followed within the chord tolerance " +
                 std::to_string(caps.chord_tolerance) + " in " + std::to_string(kMaxNurbsPoints) +
                 " line segments (" + where(call) + ")");
      return;
    }
    for (const auto& p : points)
      forward(canon::StraightFeed{{p.x, p.y, p.z, nurbs->rotary, nurbs->tool_axis}});
    return;
  }
  if (std::holds_alternative<canon::ArcFeed>(call) && caps.arcs == profile::Arcs::None) {
    report(diag::Code::RenderUnsupported, diag::Severity::Error,
           "arcs: none: linearising arcs is not implemented (" + where(call) + ")");
    return;
  }
  forward(call);
  if (const auto* e = std::get_if<canon::End>(&call); e && e->scope == canon::Scope::Workingstep)
    workingstep_.reset();
}

void Renderer::forward(const canon::Call& call) {
  if (!kinematics_) {
    if (!failed_) pass(call);  // an error stops the output; the rest is only checked
    return;
  }
  canon::Call converted = call;
  kinematics_warnings_.clear();
  if (const auto issue = kinematics_->convert(converted, kinematics_warnings_)) {
    if (!failed_)
      report(issue->code, diag::Severity::Error, issue->message + " (" + where(call) + ")");
    return;
  }
  for (auto& w : kinematics_warnings_) {
    if (kinematics_warning_count_++ < max_kinematics_warnings_)
      report(w.code, diag::Severity::Warning, w.message + " (" + where(call) + ")");
  }
  check_limits(converted);
  if (!failed_) pass(converted);
}

void Renderer::pass(const canon::Call& call) {
  if (single_chunk_)
    whole_.push_back(call);
  else
    chunker_->call(call);
}

void Renderer::render_chunk(const canon::ChunkView& chunk) {
  if (failed_) return;
  if (batch_bytes_ == 0) {
    transform_chunk(chunk);
    return;
  }
  if (batch_chunks_.empty()) {
    batch_job_ = job_;
    batch_writer_ = xml_writer_;
    batch_tool_ = tool_;
    if (batch_delay_.count() > 0) batch_started_ = std::chrono::steady_clock::now();
    tree_events_->clear();
    run_motions_.clear();
    xml_writer_.open(*tree_events_, chunk.seq);
  }
  xml_writer_.append(*tree_events_, chunk.calls, run_taker_.get());
  batch_calls_.insert(batch_calls_.end(), chunk.calls.begin(), chunk.calls.end());
  batch_chunks_.emplace_back(chunk.seq, batch_calls_.size());
  for (const auto& c : chunk.calls)
    if (const auto* t = std::get_if<canon::ChangeTool>(&c)) tool_ = t->slot;
  if (tree_events_->text_bytes() >= batch_bytes_ ||
      (batch_delay_.count() > 0 &&
       std::chrono::steady_clock::now() - batch_started_ >= batch_delay_))
    render_batch();
}

void Renderer::render_batch() {
  if (batch_chunks_.empty() || failed_) return;
  in_batch_ = true;
  xml_writer_.close(*tree_events_);
  // The tool in the spindle when the batch starts: a stylesheet cannot see a CHANGE_TOOL of an
  // earlier transform (G43 H needs it).
  params_[3].second = std::to_string(batch_tool_);
  const std::uint64_t first = batch_chunks_.front().first;
  const std::uint64_t last = batch_chunks_.back().first;
  const std::string name = input_name_ + "#chunk" + std::to_string(first) +
                           (last != first ? "-" + std::to_string(last) : std::string());
  if (!transform_tree(name, std::numeric_limits<std::uint64_t>::max()) && !cancelled_) {
    // Rendered chunk by chunk from the batch's start instead, the failure is reported as it
    // would have been without batching: the text of the chunks before the failing one is
    // written and the diagnostics name that chunk. The failed run's state and diagnostics are
    // dropped.
    job_ = batch_job_;
    xml_writer_ = batch_writer_;
    tool_ = batch_tool_;
    std::size_t begin = 0;
    for (const auto& [seq, end] : batch_chunks_) {
      transform_chunk(canon::ChunkView{
          seq, std::span<const canon::Call>(batch_calls_).subspan(begin, end - begin)});
      begin = end;
      if (failed_) break;
    }
  }
  batch_calls_.clear();
  batch_chunks_.clear();
  in_batch_ = false;
}

void Renderer::transform_chunk(const canon::ChunkView& chunk) {
  if (failed_) return;
  tree_events_->clear();
  run_motions_.clear();
  xml_writer_.append_chunk(*tree_events_, chunk, run_taker_.get());
  params_[3].second = std::to_string(tool_);
  for (const auto& c : chunk.calls)
    if (const auto* t = std::get_if<canon::ChangeTool>(&c)) tool_ = t->slot;
  (void)transform_tree(input_name_ + "#chunk" + std::to_string(chunk.seq), chunk.seq);
}

// Runs the stylesheet over tree_ and, when it succeeded, writes the text. A chunk's failure
// (`seq` names it) is reported as RENDER-002; a batch's (seq = max) is left to the caller,
// which renders its chunks one by one.
bool Renderer::transform_tree(const std::string& name, std::uint64_t seq) {
  const bool batch = seq == std::numeric_limits<std::uint64_t>::max();
  job_.set_run_motions(run_motions_);
  const auto began = std::chrono::steady_clock::now();
  auto result = xslt::transform(*profile_.stylesheet, tree_, job_, params_, name);
  transform_time_ += std::chrono::steady_clock::now() - began;
  const std::size_t unrendered = job_.run_motions_not_rendered();
  job_.set_run_motions({});
  if (result.cancelled) {
    cancelled_ = true;
    failed_ = true;
    return false;
  }
  if (result.ok && unrendered > 0) {
    result.ok = false;
    result.diagnostics.push_back(
        {name,
         diag::make(diag::Code::RenderRunNotRendered, 0, 0,
                    std::to_string(unrendered) + " of " + std::to_string(run_motions_.size()) +
                        " motions of <motions> runs were not rendered: profile '" +
                        profile_.profile.id +
                        "' sets render.motion_runs, so its stylesheet needs a template "
                        "for <motions> that calls ext:motion-run()")});
  }
  if (batch && !result.ok) return false;
  for (auto& d : result.diagnostics) diagnostics_.push_back(std::move(d));
  if (!result.ok) {
    report(diag::Code::RenderTransform, diag::Severity::Error,
           "the stylesheet of profile '" + profile_.profile.id + "' failed on chunk " +
               std::to_string(seq));
    return false;
  }
  emit(result.output);
  return true;
}

void Renderer::emit(std::string& text) {
  if (text.empty()) return;
  if (profile_.profile.line_ending != "\n") {
    std::string converted;
    converted.reserve(text.size() + text.size() / 16);
    for (char ch : text) {
      if (ch == '\n')
        converted += profile_.profile.line_ending;
      else
        converted += ch;
    }
    text.swap(converted);
  }
  started_ = true;
  out_(text);
}

void Renderer::finish() {
  if (finished_) return;
  if (!failed_ && single_chunk_ && !whole_.empty()) {
    transform_chunk(canon::ChunkView{0, whole_});
  } else if (!failed_) {
    chunker_->finish();
    if (!failed_) render_batch();
  }
  finished_ = true;
}

void Renderer::flush() {
  if (finished_ || failed_ || single_chunk_) return;
  chunker_->finish();
  if (!failed_) render_batch();
}

std::string render_program(const profile::LoadedProfile& profile,
                           std::span<const canon::Call> calls,
                           std::vector<diag::FileDiagnostic>& diagnostics, RenderOptions options) {
  std::string text;
  Renderer renderer(
      profile, [&](std::string_view piece) { text.append(piece); }, options);
  for (const auto& c : calls) renderer.call(c);
  renderer.finish();
  for (const auto& d : renderer.diagnostics()) diagnostics.push_back(d);
  return text;
}

}  // namespace ncpost::render
