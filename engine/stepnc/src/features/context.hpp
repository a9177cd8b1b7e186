#pragma once
// What every feature generator reads: the request's instances, the tool, the operation's
// common parameters, and the reporting helpers that name the instances involved.

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "generator.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features::legacy {

using p21::Instance;

// A number for a message: up to 4 decimals, trailing zeros dropped.
inline std::string fmt(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", x);
  std::string s(buffer);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

struct Toleranced {
  double size = 0;
  double upper = 0;  // allowed excess
  double lower = 0;  // allowed shortfall
};

struct Tool {
  const Instance* instance = nullptr;
  const Instance* body = nullptr;
  double radius = 0;
  std::optional<double> edge_length;     // cutting_edge_length
  std::optional<double> tip_half_angle;  // degrees
  double corner_radius = 0;              // edge_radius
  bool left_hand = false;
};

// Operation parameters shared by the generators (absent values are nullopt).
struct OperationData {
  std::optional<double> retract_plane;  // above the feature's top
  std::optional<double> axial;          // axial_cutting_depth
  std::optional<double> radial;         // radial_cutting_depth
  double allowance_side = 0;
  double allowance_bottom = 0;
  const Instance* strategy = nullptr;
  const Instance* approach = nullptr;
  const Instance* retract = nullptr;
};

class Context {
 public:
  Context(detail::GeometryReader& geometry, const Request& request, const FeatureOptions& options)
      : g(geometry), m(geometry.model()), req(request), opt(options) {}

  detail::GeometryReader& g;
  const p21::Model& m;
  const Request& req;
  const FeatureOptions& opt;
  Path path;

  const Instance& ws() const { return *req.workingstep; }
  const Instance& op() const { return *req.operation; }
  const Instance& feature() const { return *req.feature; }

  [[nodiscard]] std::string d(const Instance& i) const { return detail::describe(m, i); }
  [[nodiscard]] std::string d(const Instance* i) const { return i ? d(*i) : std::string("$"); }

  // Each returns false so that callers can `return ctx.not_implemented(...)`.
  bool not_implemented(const std::string& what) {
    g.error(diag::Code::StepncFeatureNotImplemented, ws(),
            d(ws()) + ": " + what + " is not implemented; nothing is generated");
    return false;
  }
  bool unfit(const Instance& at, const std::string& message) {
    g.error(diag::Code::StepncToolUnfit, at, message);
    return false;
  }
  bool bad(const Instance& at, const std::string& message) {
    g.error(diag::Code::StepncFeatureData, at, message);
    return false;
  }
  void note(const Instance& at, const std::string& message) {
    g.error(diag::Code::StepncNote, at, message);
  }

  // False, after reporting, when a length is beyond FeatureOptions::max_length.
  bool size_ok(const Instance& at, double value, std::string_view what) {
    if (std::abs(value) <= opt.max_length) return true;
    return bad(at, d(at) + " " + std::string(what) + " " + fmt(value) +
                       " is beyond the generator's limit of " + fmt(opt.max_length) +
                       " mm (FeatureOptions::max_length)");
  }

  [[nodiscard]] bool is(const Instance* i, std::string_view entity) const {
    return i != nullptr && g.is_a(*i, entity);
  }
  [[nodiscard]] bool set(const Instance& owner, std::string_view attribute) const {
    const auto v = g.get(owner, attribute);
    return v && !v->is_omitted();
  }
  // An optional reference; null when unset. A reference of the wrong type is reported.
  const Instance* ref(const Instance& owner, std::string_view attribute, std::string_view type) {
    if (!set(owner, attribute)) return nullptr;
    return g.instance(g.get(owner, attribute), type, &owner, attribute);
  }
  // A number attribute, nullopt when unset. Typed values (e.g. LENGTH_MEASURE(2.)) are unwrapped.
  std::optional<double> number(const Instance& owner, std::string_view attribute);
  // A toleranced_length_measure (or a plain number) attribute.
  std::optional<Toleranced> toleranced(const Instance& owner, std::string_view attribute);
  std::optional<bool> boolean(const Instance& owner, std::string_view attribute);
  std::string_view enumeration(const Instance& owner, std::string_view attribute);
  // A DIRECTION attribute in the feature's frame (normalised); nullopt when unset or bad.
  std::optional<Vec3> direction(const Instance& owner, std::string_view attribute);

  // The depth of a machining feature: its depth plane's location along -z of the feature.
  std::optional<double> depth();
  std::optional<Tool> tool();
  OperationData operation();

  void add(Move move) { path.moves.push_back(move); }
  void rapid(Vec3 to) { add({Move::Kind::Rapid, to}); }
  void feed(Vec3 to) { add({Move::Kind::Feed, to}); }
  void arc(Vec3 to, Vec3 centre, int turns) {
    Move mv{Move::Kind::Arc, to, centre};
    mv.turns = turns;
    add(mv);
  }
  [[nodiscard]] bool too_many() const { return path.moves.size() > opt.max_moves; }
  bool limit_reached() {
    return bad(ws(), d(ws()) + ": the generated path needs more than " +
                         std::to_string(opt.max_moves) +
                         " motions (FeatureOptions::max_moves); check the stepover and depths");
  }
};

bool generate_pocket(Context& ctx);
bool generate_open_pocket(Context& ctx);
bool generate_slot(Context& ctx);
bool generate_outside_profile(Context& ctx);

}  // namespace ncpost::stepnc::features::legacy
