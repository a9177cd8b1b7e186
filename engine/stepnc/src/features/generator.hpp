#pragma once
// Feature → motions, in the feature's own coordinates (its placement is the interpreter's
// business, as for explicit toolpaths). The interpreter plays the moves through the same
// approach, placement and technology code as an explicit toolpath, so both kinds of
// workingstep give the same canonical program shape (docs/features.md).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "../geometry.hpp"
#include "ncpost/stepnc/features.hpp"

namespace ncpost::stepnc::features {

using detail::Vec3;

// One step of a generated path. Coordinates are in the feature's placement frame.
struct Move {
  enum class Kind : std::uint8_t {
    Rapid,     // straight at rapid to `to`
    Feed,      // straight at the current feed to `to`
    Arc,       // circle or helix about `centre` along +z of the frame, `turns` as canon::ArcFeed
    Cycle,     // a canned hole cycle at (to.x, to.y): r_z = to.z, bottom_z = bottom
    FeedRate,  // value: mm/min
    Spindle,   // value: ISO 14649 rev/s, signed as the technology's (negative = clockwise)
    Dwell,     // value: seconds
  };
  Kind kind = Kind::Feed;
  Vec3 to{};
  Vec3 centre{};
  int turns = 1;
  double value = 0;
  // Cycle only.
  enum class CycleKind : std::uint8_t { Drill, Peck, Tap, Bore, Ream } cycle = CycleKind::Drill;
  double bottom = 0;
  double feed = 0;
  double dwell = 0;
  double peck = 0;
  double peck_retract = 0;
  double pitch = 0;
  double rpm = 0;
  bool left_hand = false;
  bool spindle_stop = false;
};

// What the interpreter knows when a workingstep needs a generated path.
struct Request {
  const p21::Instance* workingstep = nullptr;
  const p21::Instance* operation = nullptr;
  const p21::Instance* feature = nullptr;  // may be null: then nothing can be generated
  const p21::Instance* tool = nullptr;
  // The technology in force (after the operation's): mm/min and ISO rev/s (signed).
  std::optional<double> feed;
  std::optional<double> spindle;
};

struct Path {
  std::vector<Move> moves;
  bool ok = false;  // false: diagnostics say why, and nothing is to be played
};

// Reports every problem through `geometry` (which names the instance).
[[nodiscard]] Path generate(detail::GeometryReader& geometry, const Request& request,
                            const FeatureOptions& options);

}  // namespace ncpost::stepnc::features
