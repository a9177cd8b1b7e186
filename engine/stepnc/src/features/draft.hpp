#pragma once
// The path a planner draws, in the feature's coordinates (generator.hpp), the options it plans
// with and the report it tells what it cannot do. A planner takes its kind's spec and a Draft,
// and nothing of the model (docs/features.md, "Read, then plan").

#include <vector>

#include "generator.hpp"
#include "report.hpp"

namespace ncpost::stepnc::features {

class Draft {
 public:
  Draft(const FeatureOptions& options, Report& report) : options_(options), report_(report) {}

  [[nodiscard]] const FeatureOptions& options() const { return options_; }
  [[nodiscard]] Report& report() { return report_; }

  void add(const Move& move) { moves_.push_back(move); }
  void rapid(Vec3 to) { add({Move::Kind::Rapid, to}); }
  void feed(Vec3 to) { add({Move::Kind::Feed, to}); }
  // A circle or helix about `centre` along +z, `turns` as canon::ArcFeed (negative: clockwise).
  void arc(Vec3 to, Vec3 centre, int turns) {
    Move move{Move::Kind::Arc, to, centre};
    move.turns = turns;
    add(move);
  }
  // Where the last move ends; there must be one.
  [[nodiscard]] Vec3 here() const { return moves_.back().to; }
  [[nodiscard]] const std::vector<Move>& moves() const { return moves_; }

  // More moves than FeatureOptions::max_moves.
  [[nodiscard]] bool too_many() const { return moves_.size() > options_.max_moves; }
  // Reports the motion limit (STEPNC-103) and returns false.
  bool limit_reached() { return report_.limit_reached(options_.max_moves); }

  // Moves from index `first` on carried into `frame`'s parent: a planner that drew them in a
  // frame of its own (a slot's placed course of travel). `frame` must keep +z (an in-plane
  // placement), so arcs keep their sense.
  void place_from(std::size_t first, const detail::Frame& frame);

  // The path, when `ok`; else an empty one that is not to be played.
  [[nodiscard]] Path finish(bool ok) &&;

 private:
  const FeatureOptions& options_;
  Report& report_;
  std::vector<Move> moves_;
};

}  // namespace ncpost::stepnc::features
