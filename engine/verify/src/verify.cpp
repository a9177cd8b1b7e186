// The path verifier. See verify.hpp, and docs/verify.md for the algorithms and their limits.

#include "ncpost/verify/verify.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <unordered_map>

#include "cavity.hpp"
#include "model.hpp"
#include "ncpost/canon/sink.hpp"
#include "region.hpp"

namespace ncpost::verify {
namespace {

using detail::Extent;
using detail::Feature;
using detail::Frame;
using detail::Grid;
using detail::Operation;
using detail::Reader;
using detail::Region;
using detail::Tool;
using detail::Vec2;
using detail::Vec3;
using p21::Instance;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRadToDeg = 180 / std::numbers::pi;
// Gouge checks sample each move at this spacing (mm): fine next to any wall a 2.5D feature has,
// cheap enough for programs of many metres of path.
constexpr double kSampleSpacing = 0.1;
constexpr std::size_t kMaxSamplesPerMove = 20000;
// Steeper than this, a descent into material counts as a plunge for a tool that cannot cut at
// its centre (ISO 14649 has no attribute for centre cutting; see read_tool).
constexpr double kNonCentreCuttingMaxAngle = 45;
// Approach angles are compared with this slack (degrees): linearised helices are a little steep.
constexpr double kAngleSlack = 0.5;
// The tool's outline is checked against a profiled feature's section at this spacing (mm).
constexpr double kOutlineSpacing = 0.05;
// A profiled feature's coverage raster: cells times the tool's disc in cells, at most (the
// work of its two passes); coarsened beyond, with VERIFY-012.
constexpr double kMaxCavityCoverageWork = 5e7;

std::string fmt(double v, int decimals = 4) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  std::string s = buffer;
  if (s.find_first_not_of("-0.") == std::string::npos && s.front() == '-') s.erase(0, 1);
  return s;
}
std::string fmt(Vec3 p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ", " + fmt(p.z) + ")";
}
Position position(Vec3 p) {
  return {p.x, p.y, p.z};
}
Vec3 vec(const canon::Pose& p) {
  return {p.x, p.y, p.z};
}

// One straight piece of motion (arcs and NURBS are split into pieces).
struct Piece {
  Vec3 a, b;
  bool rapid = false;
  bool cycle = false;  // part of a drilling cycle's motion
};

// The stock as a height field over the machine's xy plane: for each cell, the z of the highest
// material left. Air outside the footprint. Feeds lower it under the tool; rapids are checked
// against it.
struct Stock {
  Grid grid;
  std::vector<float> top;
  bool valid = false;
};

// What the workingstep's tool sweeps of the stock along a piece: the most material (mm of
// height) above the tool's lowest point, and where. `cut` lowers the stock too.
struct Sweep {
  double removed = 0;
  Vec3 at{};
  Vec3 entry{};  // where along the piece the tool first meets material (more than `margin`)
  double entry_t = 2;
  bool over_stock = false;
};

Sweep sweep_stock(Stock& stock, const Piece& p, double radius, bool cut, double margin = 0) {
  Sweep out;
  if (!stock.valid) return out;
  const Grid& g = stock.grid;
  const Vec2 a = p.a.xy();
  const Vec2 b = p.b.xy();
  const double reach = radius + g.step;
  const int i0 =
      std::max(0, static_cast<int>(std::floor((std::min(a.x, b.x) - reach - g.origin.x) / g.step)));
  const int i1 = std::min(
      g.nx - 1, static_cast<int>(std::floor((std::max(a.x, b.x) + reach - g.origin.x) / g.step)));
  const int j0 =
      std::max(0, static_cast<int>(std::floor((std::min(a.y, b.y) - reach - g.origin.y) / g.step)));
  const int j1 = std::min(
      g.ny - 1, static_cast<int>(std::floor((std::max(a.y, b.y) + reach - g.origin.y) / g.step)));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      double t0 = 0;
      double t1 = 0;
      if (!detail::segment_within(g.centre(i, j), a, b, radius, t0, t1)) continue;
      out.over_stock = true;
      // z is linear along the piece: the lowest point within reach is at an end of [t0, t1].
      const double z0 = p.a.z + (p.b.z - p.a.z) * t0;
      const double z1 = p.a.z + (p.b.z - p.a.z) * t1;
      const double t = z0 <= z1 ? t0 : t1;
      const double z = std::min(z0, z1);
      float& h = stock.top[g.index(i, j)];
      if (h - z > out.removed) {
        out.removed = h - z;
        out.at = p.a + (p.b - p.a) * t;
      }
      if (h - z > margin && t0 < out.entry_t) {
        out.entry_t = t0;
        out.entry = p.a + (p.b - p.a) * t0;
      }
      if (cut && z < h) h = static_cast<float>(z);
    }
  }
  return out;
}

// A swept piece kept for the coverage raster, in the feature's frame.
struct Swept {
  Vec3 a, b;
  double radius = 0;
  detail::ToolShape tool;
};

// Per feature: what was read, and what the motions of its workingsteps did.
struct FeatureState {
  Feature feature;
  std::size_t report = 0;  // index in VerifyResult::features
  std::size_t workingsteps = 0;
  double min_bottom = kInf;
  double min_side = kInf;
  double min_radius = kInf;
  detail::ToolShape smallest;         // the shape of the tool of min_radius
  double min_gouge_allowance = kInf;  // profiled features: min over operations of min(a_s, a_b)
  bool any_operation = false;
  // Deepest feed position of the tool tip (feature frame z), in machine coordinates.
  double deepest_local = kInf;
  Vec3 deepest{};
  std::size_t deepest_motion = 0;
  std::size_t deepest_line = 0;
  std::uint64_t last_ws = 0;
  std::string last_ws_name;
  const Instance* last_ws_instance = nullptr;
  std::vector<Swept> swept;
};

// The worst case of one check in one workingstep: reported once, with a count.
struct Worst {
  std::size_t count = 0;
  double value = -kInf;
  Vec3 at{};
  std::size_t motion = 0;
  std::size_t line = 0;
  std::string what;
};

class Verifier final : public canon::Sink {
 public:
  Verifier(const p21::Model& model, const stepnc::AttributeReader& attributes,
           const VerifyOptions& options, VerifyResult& result)
      : r_(model, attributes), options_(options), result_(result), tol_(options.tolerance) {}

  void call(const canon::Call& c) override;
  void finish();

 private:
  // ---- structure ----
  void begin_setup(std::uint64_t id);
  void begin_workingstep(const canon::Entity& e);
  void end_workingstep();
  FeatureState* feature_state(const Instance& feature);
  Frame workpiece_frame_of(const Instance* feature) const;
  void build_stock();
  // ---- motion ----
  void move(const std::vector<Piece>& pieces);
  void stock_piece(const Piece& p);
  void feature_piece(const Piece& p);
  void check_cycle(const canon::Cycle& c);
  std::vector<Piece> arc_pieces(Vec3 start, const canon::ArcFeed& arc) const;
  std::vector<Piece> nurbs_pieces(Vec3 start, const canon::NurbsFeed& n) const;
  // ---- findings ----
  void record(diag::Code code, double value, Vec3 at, std::string what);
  void add(diag::Code code, const Instance* at, std::uint64_t ws, std::string ws_name,
           std::uint64_t feature, std::optional<Position> pos, std::size_t motion, std::size_t line,
           std::string message);
  void coverage(FeatureState& s, FeatureReport& report);
  void profiled_coverage(FeatureState& s, FeatureReport& report);

  Reader r_;
  const VerifyOptions& options_;
  VerifyResult& result_;
  double tol_;

  std::size_t calls_ = 0;
  std::size_t motions_ = 0;
  std::optional<Vec3> position_;

  // Setup: machine ← setup, and machine ← each workpiece set-up's workpiece.
  Frame setup_frame_;
  Frame default_workpiece_;
  std::vector<std::pair<std::uint64_t, Frame>> workpieces_;  // workpiece id → frame
  std::optional<double> setup_secplane_;
  const Instance* setup_ = nullptr;
  Stock stock_;
  bool stock_built_ = false;

  // Current workingstep.
  const Instance* ws_ = nullptr;
  std::uint64_t ws_id_ = 0;
  std::string ws_name_;
  FeatureState* feature_ = nullptr;
  Operation operation_;
  Tool tool_;                  // stays loaded across rapid movements, as on the machine
  std::vector<Vec2> outline_;  // its outline (ToolShape::outline), for a profiled feature
  std::optional<double> secplane_;
  std::map<diag::Code, Worst> worst_;

  std::unordered_map<std::uint64_t, std::unique_ptr<FeatureState>> features_;
  std::vector<FeatureState*> feature_order_;
};

void Verifier::call(const canon::Call& c) {
  ++calls_;
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, canon::Begin>) {
          if (v.scope == canon::Scope::Setup) begin_setup(v.entity.id);
          if (v.scope == canon::Scope::Workingstep) begin_workingstep(v.entity);
        } else if constexpr (std::is_same_v<T, canon::End>) {
          if (v.scope == canon::Scope::Workingstep) end_workingstep();
        } else if constexpr (std::is_same_v<T, canon::StraightTraverse>) {
          ++motions_;
          move({Piece{position_.value_or(vec(v.to)), vec(v.to), true}});
        } else if constexpr (std::is_same_v<T, canon::StraightFeed>) {
          ++motions_;
          move({Piece{position_.value_or(vec(v.to)), vec(v.to), false}});
        } else if constexpr (std::is_same_v<T, canon::ArcFeed>) {
          ++motions_;
          move(arc_pieces(position_.value_or(vec(v.end)), v));
        } else if constexpr (std::is_same_v<T, canon::NurbsFeed>) {
          ++motions_;
          move(nurbs_pieces(position_.value_or(Vec3{}), v));
        } else if constexpr (std::is_same_v<T, canon::Cycle>) {
          ++motions_;
          check_cycle(v);
          // The envelope of every cycle kind: over the hole at the initial level, down to the R
          // plane at rapid, feed to the bottom, back up to the initial level.
          const Vec3 safe{v.x, v.y, v.safe_z};
          const Vec3 r{v.x, v.y, v.r_z};
          const Vec3 bottom{v.x, v.y, v.bottom_z};
          std::vector<Piece> pieces;
          const Vec3 from = position_.value_or(safe);
          if (from.z < v.safe_z - 1e-9)
            pieces.push_back({from, {from.x, from.y, v.safe_z}, true, true});
          const Vec3 above = pieces.empty() ? from : pieces.back().b;
          pieces.push_back({above, safe, true, true});
          pieces.push_back({safe, r, true, true});
          pieces.push_back({r, bottom, false, true});
          pieces.push_back({bottom, safe, true, true});
          move(pieces);
        }
      },
      c);
}

// ---- structure ----------------------------------------------------------------------------

void Verifier::begin_setup(std::uint64_t id) {
  setup_ = r_.model().find(id);
  setup_frame_ = Frame{};
  workpieces_.clear();
  setup_secplane_.reset();
  stock_built_ = false;
  stock_ = Stock{};
  if (setup_ == nullptr) return;
  detail::SetupFrames frames = detail::setup_frames(r_, *setup_);
  setup_frame_ = frames.setup;
  default_workpiece_ = frames.default_workpiece;
  workpieces_ = std::move(frames.workpieces);
  if (const Instance* plane = r_.ref(*setup_, "its_secplane"))
    if (const auto f = r_.placement(r_.ref(*plane, "position")))
      setup_secplane_ = default_workpiece_.point(f->origin).z;
}

Frame Verifier::workpiece_frame_of(const Instance* feature) const {
  if (feature != nullptr) {
    if (const auto wp = r_.get(*feature, "its_workpiece"); wp && wp->is_reference()) {
      for (const auto& [id, frame] : workpieces_)
        if (id == wp->id()) return frame;
    }
  }
  return default_workpiece_;
}

FeatureState* Verifier::feature_state(const Instance& feature) {
  auto& slot = features_[feature.id];
  if (slot) return slot.get();
  slot = std::make_unique<FeatureState>();
  slot->feature = detail::read_feature(r_, feature, workpiece_frame_of(&feature));
  slot->report = result_.features.size();
  FeatureReport report;
  report.id = feature.id;
  report.type = slot->feature.type;
  report.name = r_.name(feature);
  report.checked = slot->feature.checked;
  report.not_checked_reason = slot->feature.reason;
  report.through = slot->feature.through;
  result_.features.push_back(std::move(report));
  feature_order_.push_back(slot.get());
  const auto pos = r_.where(feature);
  if (!slot->feature.checked) {
    result_.findings.push_back(
        {diag::make(diag::Code::VerifyNotChecked, pos.line, pos.column,
                    r_.describe(feature) + ": " + slot->feature.reason +
                        "; its workingsteps' rapids and plunges are still checked"),
         0,
         {},
         feature.id,
         std::nullopt,
         0,
         0});
  }
  for (const std::string& note : slot->feature.notes)
    result_.findings.push_back({diag::make(diag::Code::VerifyNote, pos.line, pos.column,
                                           r_.describe(feature) + ": " + note),
                                0,
                                {},
                                feature.id,
                                std::nullopt,
                                0,
                                0});
  return slot.get();
}

void Verifier::begin_workingstep(const canon::Entity& e) {
  ++result_.workingsteps;
  ws_ = r_.model().find(e.id);
  ws_id_ = e.id;
  ws_name_ = e.name;
  feature_ = nullptr;
  operation_ = Operation{};
  worst_.clear();
  secplane_ = setup_secplane_;
  if (ws_ == nullptr) return;
  if (const Instance* plane = r_.ref(*ws_, "its_secplane"))
    if (const auto f = r_.placement(r_.ref(*plane, "position")))
      secplane_ = default_workpiece_.point(f->origin).z;
  if (!r_.is_a(*ws_, "machining_workingstep")) return;
  const Instance* op = r_.ref(*ws_, "its_operation");
  operation_ = detail::read_operation(r_, op);
  if (op != nullptr) tool_ = detail::read_tool(r_, r_.ref(*op, "its_tool"), options_.interpret);
  if (const Instance* f = r_.ref(*ws_, "its_feature")) {
    feature_ = feature_state(*f);
    FeatureState& s = *feature_;
    ++s.workingsteps;
    s.last_ws = ws_id_;
    s.last_ws_name = ws_name_;
    s.last_ws_instance = ws_;
    if (op != nullptr) {
      s.any_operation = true;
      s.min_side = std::min(s.min_side, operation_.side_allowance);
      if (operation_.has_bottom_allowance || !operation_.hole_making)
        s.min_bottom = std::min(s.min_bottom, operation_.bottom_allowance);
    }
    if (tool_.known && tool_.radius < s.min_radius) {
      s.min_radius = tool_.radius;
      s.smallest = tool_.shape;
    }
    if (op != nullptr)
      s.min_gouge_allowance = std::min(
          s.min_gouge_allowance, std::min(operation_.side_allowance, operation_.bottom_allowance));
    // The tool's outline for the profiled features' gouge check, down to well below the floor.
    outline_.clear();
    if (s.feature.cavity && tool_.known)
      outline_ = tool_.shape.outline(kOutlineSpacing, 2 * -s.feature.floor + 2);
    if (s.feature.cavity) s.feature.cavity->forget();
  }
}

void Verifier::end_workingstep() {
  for (auto& [code, w] : worst_) {
    std::string message =
        (ws_id_ != 0 ? "workingstep #" + std::to_string(ws_id_) + " '" + ws_name_ + "': "
                     : std::string("outside any workingstep: ")) +
        w.what + " at " + fmt(w.at) + ", motion " + std::to_string(w.motion) + " (trace line " +
        std::to_string(w.line) + ")";
    if (w.count > 1) message += "; " + std::to_string(w.count) + " such positions in all";
    add(code, ws_, ws_id_, ws_name_, feature_ ? feature_->feature.instance->id : 0, position(w.at),
        w.motion, w.line, std::move(message));
  }
  worst_.clear();
  ws_ = nullptr;
  ws_id_ = 0;
  ws_name_.clear();
  feature_ = nullptr;
  operation_ = Operation{};
}

void Verifier::build_stock() {
  stock_built_ = true;
  // The workpieces of the setup (or of the program, without a setup): their BLOCK when they
  // have one, else the footprint of their features up to the highest feature top.
  std::vector<const Instance*> workpieces;
  if (!workpieces_.empty()) {
    for (const auto& [id, frame] : workpieces_)
      if (const Instance* w = r_.model().find(id)) workpieces.push_back(w);
  } else {
    workpieces = r_.model().instances_of("WORKPIECE");
  }
  Extent extent;
  bool from_features = false;
  for (const Instance* wp : workpieces) {
    const Frame frame = [&] {
      for (const auto& [id, f] : workpieces_)
        if (id == wp->id) return f;
      return default_workpiece_;
    }();
    if (const auto block = detail::workpiece_block(r_, *wp, frame)) {
      extent.add({block->min.x, block->min.y, 0});
      extent.add({block->max.x, block->max.y, 0});
      extent.top = std::max(extent.top, block->top);
      continue;
    }
    for (const Instance& i : r_.model().instances()) {
      if (i.id == 0 || !r_.is_a(i, "manufacturing_feature")) continue;
      const auto w = r_.get(i, "its_workpiece");
      if (!w || !w->is_reference() || w->id() != wp->id) continue;
      const Feature f = detail::read_feature(r_, i, frame);
      if (!f.has_outline()) continue;
      const Extent e = detail::feature_extent(f);
      extent.add({e.min.x, e.min.y, 0});
      extent.add({e.max.x, e.max.y, 0});
      extent.top = std::max(extent.top, e.top);
      from_features = true;
    }
  }
  if (!extent.valid()) return;
  Grid g;
  g.step = std::max(options_.stock_grid, 1e-3);
  const double w = extent.max.x - extent.min.x;
  const double h = extent.max.y - extent.min.y;
  while ((w / g.step + 1) * (h / g.step + 1) > static_cast<double>(options_.max_cells))
    g.step *= 1.25;
  g.origin = extent.min;
  g.nx = static_cast<int>(std::ceil(w / g.step)) + 1;
  g.ny = static_cast<int>(std::ceil(h / g.step)) + 1;
  stock_.grid = g;
  stock_.top.assign(g.cells(), static_cast<float>(extent.top));
  stock_.valid = true;
  if (from_features && setup_ != nullptr) {
    const auto pos = r_.where(*setup_);
    result_.findings.push_back(
        {diag::make(diag::Code::VerifyNote, pos.line, pos.column,
                    r_.describe(*setup_) +
                        ": the workpiece has no BLOCK bounding geometry; the stock is taken as "
                        "the features' footprint x " +
                        fmt(extent.min.x) + ".." + fmt(extent.max.x) + ", y " + fmt(extent.min.y) +
                        ".." + fmt(extent.max.y) + " up to z " + fmt(extent.top)),
         0,
         {},
         0,
         std::nullopt,
         0,
         0});
  }
}

// ---- motion -------------------------------------------------------------------------------

std::vector<Piece> Verifier::arc_pieces(Vec3 start, const canon::ArcFeed& arc) const {
  Vec3 n{arc.normal.i, arc.normal.j, arc.normal.k};
  const double nl = n.length();
  const Vec3 end = vec(arc.end);
  if (nl < 1e-12 || arc.turns == 0) return {Piece{start, end, false}};
  n = n * (1 / nl);
  const Vec3 c{arc.centre.x, arc.centre.y, arc.centre.z};
  const Vec3 u = (start - c) - n * (start - c).dot(n);
  const Vec3 v = (end - c) - n * (end - c).dot(n);
  const double radius = u.length();
  if (radius < 1e-9) return {Piece{start, end, false}};
  const Vec3 e1 = u * (1 / radius);
  const Vec3 e2 = n.cross(e1);
  double theta = std::atan2(v.dot(e2), v.dot(e1));  // (-pi, pi], counter-clockwise about n
  const double full = detail::kTwoPi;
  double sweep = 0;
  const int turns = std::abs(arc.turns);
  if (arc.turns > 0) {
    if (theta <= 1e-12) theta += full;
    sweep = theta + (turns - 1) * full;
  } else {
    double cw = -theta;
    if (cw <= 1e-12) cw += full;
    sweep = -(cw + (turns - 1) * full);
  }
  const double h0 = (start - c).dot(n);
  const double h1 = (end - c).dot(n);
  const double v_radius = v.length();
  // Chord error at most a quarter of the tolerance.
  const double e = std::max(tol_ / 4, 1e-4);
  const double step = radius > e ? std::min(2 * std::acos(1 - e / radius), 0.2) : 0.2;
  const int count = std::clamp(static_cast<int>(std::ceil(std::abs(sweep) / step)), 1, 100000);
  std::vector<Piece> out;
  out.reserve(static_cast<std::size_t>(count));
  Vec3 previous = start;
  for (int k = 1; k <= count; ++k) {
    const double t = static_cast<double>(k) / count;
    const double a = sweep * t;
    const double rr = radius + (v_radius - radius) * t;
    const Vec3 p = k == count
                       ? end
                       : c + (e1 * std::cos(a) + e2 * std::sin(a)) * rr + n * (h0 + (h1 - h0) * t);
    out.push_back({previous, p, false});
    previous = p;
  }
  return out;
}

std::vector<Piece> Verifier::nurbs_pieces(Vec3 start, const canon::NurbsFeed& nurbs) const {
  if (!canon::valid(nurbs)) return {};
  const auto& P = nurbs.points;
  const auto& U = nurbs.knots;
  const int p = nurbs.degree;
  const int n = static_cast<int>(P.size()) - 1;
  const double u0 = U[static_cast<std::size_t>(p)];
  const double u1 = U[static_cast<std::size_t>(n + 1)];
  std::vector<std::array<double, 4>> weighted;
  for (const auto& q : P) weighted.push_back({q.x, q.y, q.z, q.weight});
  const auto eval = [&](double u) { return detail::de_boor(weighted, U, p, u); };
  double polygon = 0;
  for (std::size_t k = 1; k < P.size(); ++k)
    polygon += (Vec3{P[k].x, P[k].y, P[k].z} - Vec3{P[k - 1].x, P[k - 1].y, P[k - 1].z}).length();
  const int count = std::clamp(static_cast<int>(std::ceil(polygon / kSampleSpacing)),
                               8 * static_cast<int>(P.size()), 100000);
  std::vector<Piece> out;
  Vec3 previous = start;
  for (int k = 1; k <= count; ++k) {
    const Vec3 q =
        k == count ? Vec3{P.back().x, P.back().y, P.back().z} : eval(u0 + (u1 - u0) * k / count);
    out.push_back({previous, q, false});
    previous = q;
  }
  return out;
}

void Verifier::move(const std::vector<Piece>& pieces) {
  if (!stock_built_) build_stock();
  // The stock is swept along chords of the fine pieces that stay within a quarter of its cell
  // of them: each sweep visits every cell under the tool, so a helix split for the 0.01 mm wall
  // check would cost hundreds of times more there for nothing.
  const double deviation = std::max(tol_, stock_.grid.step / 4);
  std::size_t first = 0;
  while (first < pieces.size()) {
    std::size_t last = first;
    while (last + 1 < pieces.size() && last + 1 - first < 64 &&
           pieces[last + 1].rapid == pieces[first].rapid &&
           pieces[last + 1].cycle == pieces[first].cycle) {
      const Vec3 a = pieces[first].a;
      const Vec3 b = pieces[last + 1].b;
      const Vec3 d = b - a;
      const double len2 = d.dot(d);
      bool close = true;
      for (std::size_t k = first; k <= last && close; ++k) {
        const Vec3 q = pieces[k].b - a;
        const double t = len2 > 0 ? std::clamp(q.dot(d) / len2, 0.0, 1.0) : 0.0;
        close = (q - d * t).length() <= deviation;
      }
      if (!close) break;
      ++last;
    }
    stock_piece({pieces[first].a, pieces[last].b, pieces[first].rapid, pieces[first].cycle});
    first = last + 1;
  }
  for (const Piece& p : pieces) feature_piece(p);
  if (!pieces.empty()) position_ = pieces.back().b;
}

void Verifier::record(diag::Code code, double value, Vec3 at, std::string what) {
  Worst& w = worst_[code];
  ++w.count;
  // The first of equal worst cases (up to rounding) is the one reported: stable positions.
  if (value > w.value + 1e-9) {
    w.value = value;
    w.at = at;
    w.motion = motions_;
    w.line = calls_;
    w.what = std::move(what);
  }
}

void Verifier::stock_piece(const Piece& p) {
  const double radius = tool_.known ? tool_.radius : 0;
  // ---- stock: rapids may not enter it; feeds remove it ----
  if (p.rapid) {
    // A rapid into the stock is reported once: the crash removes that material too, so the
    // retract out of it is not reported again.
    const Sweep s = sweep_stock(stock_, p, std::max(radius - tol_, 0.0), false, tol_);
    if (s.removed > tol_) sweep_stock(stock_, p, radius, true);
    const bool below = secplane_ && std::min(p.a.z, p.b.z) < *secplane_ - tol_;
    if (s.removed > tol_) {
      record(diag::Code::VerifyRapid, s.removed, s.entry,
             "a rapid " +
                 std::string(below ? "below the security plane (z " + fmt(*secplane_) + ") " : "") +
                 "goes " + fmt(s.removed) + " mm into the stock, entering it");
    } else if (below && s.over_stock) {
      ++result_.rapids_below_secplane_in_air;
    }
  } else {
    const Sweep s = sweep_stock(stock_, p, radius, true);
    // A descent into material: is it a plunge the strategy or the tool forbids?
    const double drop = p.a.z - p.b.z;
    if (ws_ != nullptr && operation_.instance != nullptr && !operation_.hole_making &&
        !tool_.hole_making && !p.cycle && drop > tol_ && s.removed > tol_) {
      const double angle = std::atan2(drop, (p.b.xy() - p.a.xy()).length()) * kRadToDeg;
      std::optional<double> limit;
      std::string why;
      using A = Operation::Approach;
      if (operation_.approach == A::Ramp || operation_.approach == A::Helix ||
          operation_.approach == A::Zigzag) {
        limit = operation_.approach_angle.value_or(kNonCentreCuttingMaxAngle);
        why = "the approach strategy " + r_.describe(*operation_.approach_instance) +
              " allows at most " + fmt(*limit, 1) + " deg";
      } else if (!tool_.centre_cutting) {
        limit = kNonCentreCuttingMaxAngle;
        why = "the tool (" + tool_.body + ") does not cut at its centre; at most " +
              fmt(*limit, 1) + " deg";
      }
      if (limit && angle > *limit + kAngleSlack)
        record(diag::Code::VerifyPlunge, angle, s.at,
               "a feed descends " + fmt(s.removed) + " mm into material at " + fmt(angle, 1) +
                   " deg; " + why);
    }
  }
}

void Verifier::feature_piece(const Piece& p) {
  const double radius = tool_.known ? tool_.radius : 0;
  if (feature_ == nullptr || !feature_->feature.checked) return;
  FeatureState& fs = *feature_;
  const Feature& f = fs.feature;
  const Vec3 la = f.frame.local(p.a);
  const Vec3 lb = f.frame.local(p.b);
  // Only pieces that can reach the final depth matter for coverage: that depth is at most this
  // operation's own (floor + its bottom allowance), so anything higher is not kept.
  const double keep_below =
      f.cavity ? 0 : f.floor + (f.through ? 0 : operation_.bottom_allowance) + tol_;
  if (!p.rapid && std::min(la.z, lb.z) <= keep_below)
    fs.swept.push_back({la, lb, radius, tool_.shape});
  // Drilling cycles in a hole are checked as cycles (check_cycle), not sample by sample.
  if (p.cycle && f.kind == Feature::Kind::Hole) {
    if (!p.rapid && lb.z < fs.deepest_local) {
      fs.deepest_local = lb.z;
      fs.deepest = p.b;
      fs.deepest_motion = motions_;
      fs.deepest_line = calls_;
    }
    return;
  }
  const double side = operation_.side_allowance;
  const double bottom_limit = f.floor + operation_.bottom_allowance - f.cone_depth;
  const double length = (lb - la).length();
  const std::size_t samples = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::ceil(length / kSampleSpacing)), 1, kMaxSamplesPerMove);
  for (std::size_t k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(samples);
    const Vec3 q = la + (lb - la) * t;
    if (q.z >= -tol_) continue;  // above the feature's top: nothing of it to touch
    // Below the top the tool's widest part that is inside the feature: a ball's is narrower
    // within one radius of its tip.
    double reach = radius;
    if (tool_.ball && -q.z < radius)
      reach = std::sqrt(std::max(0.0, radius * radius - (radius + q.z) * (radius + q.z)));
    if (f.cavity) {
      // The tool's whole shape against the cavity's walls and floor (cavity.hpp).
      const double allowance = std::min(side, operation_.bottom_allowance);
      Vec3 where{};
      const double over = f.cavity->violation(q, tool_.shape, outline_, allowance, &where);
      if (over > tol_)
        record(diag::Code::VerifyGouge, over, f.frame.point(q),
               "the tool (" + tool_.body + ", radius " + fmt(radius) + ") cuts " + fmt(over) +
                   " mm into " + r_.describe(*f.instance) + " (allowance " + fmt(allowance) +
                   ", deepest at z " + fmt(f.frame.point(where).z) + ")");
    }
    // Distance into where the tool may be: inside a pocket's outline, outside a profile's.
    const double d = f.cavity    ? f.cavity->floor_distance(q.xy())
                     : f.outside ? -f.region.signed_distance(q.xy())
                                 : f.region.signed_distance(q.xy());
    const double d_floor =
        f.floor_region && !f.cavity ? f.floor_region->signed_distance(q.xy()) : d;
    if (f.walls && !f.cavity) {
      const double over = reach + side - d;
      if (over > tol_)
        record(diag::Code::VerifyGouge, over, f.frame.point(q),
               "the tool (radius " + fmt(radius) + ") crosses the wall of " +
                   r_.describe(*f.instance) + " by " + fmt(over) + " mm (side allowance " +
                   fmt(side) + ")");
    }
    // An outside profile's floor is a band round it at most a tool radius wide (the smallest
    // tool's): this tool overlaps it within its own diameter of the allowance.
    const bool overlaps = f.outside ? d < side + 2 * radius + tol_ : d_floor > -radius;
    if (!f.through && overlaps && q.z < bottom_limit - tol_)
      record(diag::Code::VerifyBelowFloor, bottom_limit - q.z, f.frame.point(q),
             "the tool goes " + fmt(bottom_limit - q.z) + " mm below the floor of " +
                 r_.describe(*f.instance) + " (floor z " + fmt(f.frame.point({0, 0, f.floor}).z) +
                 " + bottom allowance " + fmt(operation_.bottom_allowance) + ")");
    if (!p.rapid && overlaps && q.z < fs.deepest_local) {
      fs.deepest_local = q.z;
      fs.deepest = f.frame.point(q);
      fs.deepest_motion = motions_;
      fs.deepest_line = calls_;
    }
  }
}

void Verifier::check_cycle(const canon::Cycle& c) {
  if (feature_ == nullptr || !feature_->feature.checked ||
      feature_->feature.kind != Feature::Kind::Hole)
    return;
  const Feature& f = feature_->feature;
  const Vec3 at{c.x, c.y, c.bottom_z};
  const Vec3 local = f.frame.local(at);
  const double off = local.xy().length();
  if (off > tol_)
    record(diag::Code::VerifyCycle, off, at,
           std::string(canon::name(c.kind)) + " is " + fmt(off) + " mm off the axis of " +
               r_.describe(*f.instance));
  if (tool_.known && tool_.radius > f.hole_radius + tol_)
    record(diag::Code::VerifyCycle, tool_.radius - f.hole_radius, at,
           std::string(canon::name(c.kind)) + " with a tool of diameter " + fmt(2 * tool_.radius) +
               " in " + r_.describe(*f.instance) + " of diameter " + fmt(2 * f.hole_radius));
  const double floor_z = f.frame.point({0, 0, f.floor}).z;
  if (!f.through && c.bottom_z < floor_z - f.cone_depth - tol_)
    record(diag::Code::VerifyCycle, floor_z - c.bottom_z, at,
           std::string(canon::name(c.kind)) + " goes " + fmt(floor_z - c.bottom_z) +
               " mm below the floor of " + r_.describe(*f.instance) + " (z " + fmt(floor_z) + ")");
  if (!operation_.spot && c.bottom_z > floor_z + operation_.bottom_allowance + tol_)
    record(diag::Code::VerifyCycle, c.bottom_z - floor_z, at,
           std::string(canon::name(c.kind)) + " stops " + fmt(c.bottom_z - floor_z) +
               " mm above the " + (f.through ? "bottom" : "floor") + " of " +
               r_.describe(*f.instance) + " (z " + fmt(floor_z) + ")");
}

// ---- findings -----------------------------------------------------------------------------

void Verifier::add(diag::Code code, const Instance* at, std::uint64_t ws, std::string ws_name,
                   std::uint64_t feature, std::optional<Position> pos, std::size_t motion,
                   std::size_t line, std::string message) {
  p21::LineIndex::Position where{0, 0};
  if (at != nullptr) where = r_.where(*at);
  result_.findings.push_back({diag::make(code, where.line, where.column, std::move(message)), ws,
                              std::move(ws_name), feature, pos, motion, line});
}

void Verifier::coverage(FeatureState& s, FeatureReport& report) {
  const Feature& f = s.feature;
  const double radius = s.min_radius;
  if (!std::isfinite(radius) || radius <= 0) return;
  if (f.cavity) {
    profiled_coverage(s, report);
    return;
  }
  const double side = std::isfinite(s.min_side) ? s.min_side : 0;
  const double target =
      report.through ? f.floor : f.floor + (std::isfinite(s.min_bottom) ? s.min_bottom : 0);
  Grid g;
  g.step = options_.grid.value_or(std::clamp(radius / 20, 0.05, 1.0));
  // An outside profile's floor band lies round its outline.
  const double band = f.outside ? radius : 0;
  const double around = f.outside ? side + band + 2 * radius : 0;
  const Vec2 lo = f.floor_outline().min() - Vec2{around, around};
  const Vec2 hi = f.floor_outline().max() + Vec2{around, around};
  const auto fit = [&] {
    g.nx = static_cast<int>(std::ceil((hi.x - lo.x) / g.step)) + 2;
    g.ny = static_cast<int>(std::ceil((hi.y - lo.y) / g.step)) + 2;
  };
  fit();
  bool coarsened = false;
  while (g.cells() > options_.max_cells) {
    g.step *= 1.25;
    fit();
    coarsened = true;
  }
  g.origin = {lo.x - g.step, lo.y - g.step};
  if (coarsened && s.last_ws_instance != nullptr)
    add(diag::Code::VerifyGridCoarsened, f.instance, 0, {}, f.instance->id, std::nullopt, 0, 0,
        r_.describe(*f.instance) + ": the coverage grid was coarsened to " + fmt(g.step) +
            " mm to stay within " + std::to_string(options_.max_cells) + " cells");
  // The floor after this feature's operations (inset by the side allowance), and the part of it
  // a tool of `radius` reaches: within `radius` of a centre that keeps clear of the walls.
  // Cell centres sample the continuous sets: a centre position that is allowed may lie up to
  // half a cell diagonal from the nearest cell centre. Both the allowed centres and the swept
  // radius get that slack, so a path that is exactly right covers every reachable cell, and a
  // hole made by a tool of its own diameter (one allowed centre point) is measured at all.
  const double slack = std::max(tol_, g.step * std::numbers::sqrt2 / 2);
  std::vector<float> distance(g.cells());
  std::vector<unsigned char> centre_ok(g.cells(), 0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double d = f.outside ? -f.region.signed_distance(g.centre(i, j))
                                 : f.region.signed_distance(g.centre(i, j));
      distance[g.index(i, j)] =
          static_cast<float>(f.floor_region ? f.floor_region->signed_distance(g.centre(i, j)) : d);
      centre_ok[g.index(i, j)] = !f.walls || d >= radius + side - slack;
    }
  const std::vector<float> to_centre = detail::distance_to_seeds(g, centre_ok);
  // Swept at the final depth: every feed piece, clipped to where the tip is within the
  // tolerance of the target, widened by its tool's radius.
  std::vector<unsigned char> covered(g.cells(), 0);
  const double level = target + tol_;
  for (const Swept& w : s.swept) {
    if (std::min(w.a.z, w.b.z) > level) continue;
    Vec3 a = w.a;
    Vec3 b = w.b;
    if (a.z > level || b.z > level) {
      const double t = (level - a.z) / (b.z - a.z);
      const Vec3 m = a + (b - a) * t;
      if (a.z > level)
        a = m;
      else
        b = m;
    }
    const double reach = w.radius + slack;
    const int i0 = std::max(
        0, static_cast<int>(std::floor((std::min(a.x, b.x) - reach - g.origin.x) / g.step)));
    const int i1 = std::min(
        g.nx - 1, static_cast<int>(std::floor((std::max(a.x, b.x) + reach - g.origin.x) / g.step)));
    const int j0 = std::max(
        0, static_cast<int>(std::floor((std::min(a.y, b.y) - reach - g.origin.y) / g.step)));
    const int j1 = std::min(
        g.ny - 1, static_cast<int>(std::floor((std::max(a.y, b.y) + reach - g.origin.y) / g.step)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (!covered[g.index(i, j)] &&
            detail::segment_distance(g.centre(i, j), a.xy(), b.xy()) <= reach)
          covered[g.index(i, j)] = 1;
  }
  std::size_t reachable = 0;
  std::size_t unreachable = 0;
  std::size_t uncovered = 0;
  Vec2 sum{};
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = g.index(i, j);
      if (distance[c] < side || (f.outside && distance[c] > side + band)) continue;  // not floor
      if (static_cast<double>(to_centre[c]) * g.step > radius) {
        ++unreachable;
        continue;
      }
      ++reachable;
      if (!covered[c]) {
        ++uncovered;
        sum = sum + g.centre(i, j);
      }
    }
  const double cell = g.step * g.step;
  report.coverage_checked = true;
  report.grid = g.step;
  report.tool_radius = radius;
  report.reachable_area = static_cast<double>(reachable) * cell;
  report.unreachable_area = static_cast<double>(unreachable) * cell;
  report.uncovered_fraction =
      reachable ? static_cast<double>(uncovered) / static_cast<double>(reachable) : 0;
  if (uncovered == 0) return;
  // A sample in the middle of what is missed: the uncovered cell nearest their centroid.
  const Vec2 centroid = sum * (1.0 / static_cast<double>(uncovered));
  Vec2 best{};
  double best_d = kInf;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = g.index(i, j);
      if (distance[c] < side || (f.outside && distance[c] > side + band) || covered[c] ||
          static_cast<double>(to_centre[c]) * g.step > radius)
        continue;
      const double d = (g.centre(i, j) - centroid).length();
      if (d < best_d) {
        best_d = d;
        best = g.centre(i, j);
      }
    }
  const Vec3 sample = f.frame.point({best.x, best.y, target});
  report.uncovered_sample = position(sample);
  add(diag::Code::VerifyCoverage, s.last_ws_instance, s.last_ws, s.last_ws_name, f.instance->id,
      position(sample), 0, 0,
      r_.describe(*f.instance) + ": " + fmt(100 * report.uncovered_fraction, 2) +
          "% of the floor that a tool of radius " + fmt(radius) + " reaches (" +
          fmt(report.reachable_area, 1) + " mm2) is not swept at z " + fmt(report.target_z) +
          " (grid " + fmt(g.step) + " mm, tolerance " + fmt(tol_) + " mm), e.g. at " + fmt(sample) +
          " (last workingstep #" + std::to_string(s.last_ws) + " '" + s.last_ws_name + "')");
}

void Verifier::profiled_coverage(FeatureState& s, FeatureReport& report) {
  const Feature& f = s.feature;
  if (!f.coverage) return;
  std::vector<detail::SweptShape> swept;
  swept.reserve(s.swept.size());
  for (const Swept& w : s.swept) swept.push_back({w.a, w.b, w.tool});
  const double allowance = std::isfinite(s.min_gouge_allowance) ? s.min_gouge_allowance : 0;
  const detail::CavityCoverage c = detail::cover(*f.cavity, swept, s.smallest, allowance, tol_,
                                                 options_.grid, kMaxCavityCoverageWork);
  if (c.coarsened && s.last_ws_instance != nullptr)
    add(diag::Code::VerifyGridCoarsened, f.instance, 0, {}, f.instance->id, std::nullopt, 0, 0,
        r_.describe(*f.instance) + ": the coverage grid was coarsened to " + fmt(c.grid) +
            " mm to bound the work of its surface coverage");
  report.coverage_checked = true;
  report.grid = c.grid;
  report.tool_radius = s.min_radius;
  report.reachable_area = c.reachable_area;
  report.unreachable_area = c.unreachable_area;
  report.uncovered_fraction = c.uncovered_fraction;
  if (c.uncovered == 0) return;
  const Vec3 sample = f.frame.point(c.sample);
  report.uncovered_sample = position(sample);
  add(diag::Code::VerifyCoverage, s.last_ws_instance, s.last_ws, s.last_ws_name, f.instance->id,
      position(sample), 0, 0,
      r_.describe(*f.instance) + ": " + fmt(100 * report.uncovered_fraction, 2) +
          "% of the surface that a tool of radius " + fmt(s.min_radius) + " reaches (" +
          fmt(report.reachable_area, 1) +
          " mm2 in plan) is left more than the tolerance above "
          "it (grid " +
          fmt(c.grid) + " mm, tolerance " + fmt(tol_) + " mm along the surface), e.g. at " +
          fmt(sample) + " (last workingstep #" + std::to_string(s.last_ws) + " '" + s.last_ws_name +
          "')");
}

void Verifier::finish() {
  end_workingstep();  // what happened after the last workingstep (the final retract)
  result_.calls = calls_;
  result_.motions = motions_;
  const std::atomic<bool>* cancel = options_.interpret.cancel;
  for (FeatureState* s : feature_order_) {
    // A feature's coverage can take seconds (a raster of up to max_cells against every pass).
    if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) {
      result_.cancelled = true;
      return;
    }
    FeatureReport& report = result_.features[s->report];
    report.workingsteps = s->workingsteps;
    const Feature& f = s->feature;
    if (!f.checked) continue;
    const double bottom = report.through ? 0 : (std::isfinite(s->min_bottom) ? s->min_bottom : 0);
    report.floor_z = f.frame.point({0, 0, f.floor}).z;
    report.target_z = f.frame.point({0, 0, f.floor + bottom}).z;
    if (std::isfinite(s->deepest_local)) report.deepest = position(s->deepest);
    report.depth_reached = s->deepest_local <= f.floor + bottom + tol_;
    if (!report.depth_reached) {
      std::string message =
          r_.describe(*f.instance) + ": the final depth z " + fmt(report.target_z) + " (" +
          (report.through ? std::string("through its bottom")
                          : "floor " + fmt(report.floor_z) + " + bottom allowance " + fmt(bottom)) +
          ") is not reached; ";
      if (report.deepest)
        message += "the deepest feed is at " + fmt(s->deepest) + ", motion " +
                   std::to_string(s->deepest_motion) + " (trace line " +
                   std::to_string(s->deepest_line) + ")";
      else
        message += "no feed goes below its top";
      message +=
          " (last workingstep #" + std::to_string(s->last_ws) + " '" + s->last_ws_name + "')";
      add(diag::Code::VerifyDepth, s->last_ws_instance, s->last_ws, s->last_ws_name, f.instance->id,
          report.deepest ? std::optional<Position>(report.deepest) : std::nullopt,
          s->deepest_motion, s->deepest_line, std::move(message));
    }
    coverage(*s, report);
  }
}

}  // namespace

bool VerifyResult::ok() const {
  const auto error = [](const diag::Diagnostic& d) { return d.severity == diag::Severity::Error; };
  return !cancelled && std::none_of(interpreter.begin(), interpreter.end(), error) &&
         std::none_of(findings.begin(), findings.end(),
                      [&](const Finding& f) { return error(f.diagnostic); });
}

VerifyResult verify(const p21::Model& model, const stepnc::AttributeReader& attributes,
                    const VerifyOptions& options) {
  VerifyResult result;
  result.tolerance = options.tolerance;
  Verifier verifier(model, attributes, options, result);
  auto interpreted = stepnc::interpret(model, attributes, verifier, options.interpret);
  verifier.finish();
  result.interpreter = std::move(interpreted.diagnostics);
  const std::atomic<bool>* cancel = options.interpret.cancel;
  result.cancelled =
      result.cancelled || (cancel != nullptr && cancel->load(std::memory_order_relaxed));
  return result;
}

VerifyResult verify_calls(const p21::Model& model, const stepnc::AttributeReader& attributes,
                          std::span<const canon::Call> calls, const VerifyOptions& options) {
  VerifyResult result;
  result.tolerance = options.tolerance;
  Verifier verifier(model, attributes, options, result);
  for (const canon::Call& c : calls) verifier.call(c);
  verifier.finish();
  return result;
}

std::vector<StockBox> stock_boxes(const p21::Model& model,
                                  const stepnc::AttributeReader& attributes) {
  const detail::Reader r(model, attributes);
  std::vector<StockBox> out;
  const auto add = [&](const Instance& workpiece, const Frame& frame, std::uint64_t setup) {
    const auto corners = detail::workpiece_block_corners(r, workpiece, frame);
    if (!corners) return;
    StockBox box{workpiece.id, r.name(workpiece), setup, {}};
    for (const Vec3& c : *corners) box.corners.push_back({c.x, c.y, c.z});
    out.push_back(std::move(box));
  };
  const auto setups = model.instances_of("SETUP");
  if (setups.empty()) {
    for (const Instance* w : model.instances_of("WORKPIECE")) add(*w, Frame{}, 0);
    return out;
  }
  for (const Instance* setup : setups) {
    for (const auto& [id, frame] : detail::setup_frames(r, *setup).workpieces)
      if (const Instance* w = id != 0 ? model.find(id) : nullptr) add(*w, frame, setup->id);
  }
  return out;
}

}  // namespace ncpost::verify
