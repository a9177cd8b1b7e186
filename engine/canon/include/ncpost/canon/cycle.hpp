#pragma once
// Expanding a high-level cycle into plain canonical motions, for profiles whose controller
// has no such canned cycle. In: a Cycle. Out: calls on a Sink, as a G8x controller would move.
//
// Every expansion starts with
//   SET_FEED_RATE(feed)
//   STRAIGHT_TRAVERSE(x, y, safe_z)        rapid to the hole position at the safe plane
//   STRAIGHT_TRAVERSE(x, y, r_z)           rapid down to the R plane
// then, by kind (z0 = r_z, zb = bottom_z):
//   Drill (G81, G82 with dwell):
//     STRAIGHT_FEED(x, y, zb)  [DWELL(dwell)]  STRAIGHT_TRAVERSE(x, y, safe_z)
//   PeckDrill, peck_retract == 0 (G83): peck n (n = 1, 2, ...) ends at
//   d_n = max(z0 - n·peck, zb); before every peck but the first,
//     STRAIGHT_TRAVERSE(x, y, d_{n-1} + peck_clearance)
//   then STRAIGHT_FEED(x, y, d_n), then, unless d_n is the bottom, STRAIGHT_TRAVERSE(x, y, z0).
//   At the bottom: [DWELL(dwell)]  STRAIGHT_TRAVERSE(x, y, safe_z)
//   PeckDrill, peck_retract > 0 (G73): STRAIGHT_FEED(x, y, d_n), then, unless d_n is the
//   bottom, STRAIGHT_TRAVERSE(x, y, d_n + peck_retract); at the bottom as G83.
//   Tap (G84; left_hand swaps the two spindle directions):
//     STRAIGHT_FEED(x, y, zb)  STOP_SPINDLE_TURNING()  START_SPINDLE_COUNTERCLOCKWISE()
//     [DWELL(dwell)]  STRAIGHT_FEED(x, y, z0)  STOP_SPINDLE_TURNING()
//     START_SPINDLE_CLOCKWISE()  STRAIGHT_TRAVERSE(x, y, safe_z)
//   Bore, spindle_stop == false, and Ream (G85, G89 with dwell):
//     STRAIGHT_FEED(x, y, zb)  [DWELL(dwell)]  STRAIGHT_FEED(x, y, z0)
//     STRAIGHT_TRAVERSE(x, y, safe_z)
//   Bore, spindle_stop == true (G86):
//     STRAIGHT_FEED(x, y, zb)  [DWELL(dwell)]  STOP_SPINDLE_TURNING()
//     STRAIGHT_TRAVERSE(x, y, safe_z)  START_SPINDLE_CLOCKWISE()
// [DWELL] appears only when dwell > 0. Every motion carries the cycle's rotary axes and tool
// axis. The spindle is assumed to turn clockwise when the cycle starts (counter-clockwise for
// a left-hand tap); the expansion leaves it turning that way, and leaves the feed rate at
// `feed`.

#include <cstddef>
#include <string_view>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"

namespace ncpost::canon {

enum class CycleError : std::uint8_t {
  None,
  NotFinite,      // a number is NaN or infinite
  BadHeights,     // not safe_z >= r_z >= bottom_z
  BadFeed,        // feed <= 0
  BadPeck,        // PeckDrill with peck <= 0, or peck_retract / peck_clearance < 0
  TooManyPecks,   // (r_z - bottom_z) / peck exceeds ExpandOptions::max_pecks
  NegativeDwell,  // dwell < 0
};

[[nodiscard]] std::string_view describe(CycleError error) noexcept;

struct ExpandOptions {
  // Pecks in one PeckDrill expansion at most; a tiny peck over a deep hole would otherwise
  // produce an unbounded number of motions.
  std::size_t max_pecks = 10000;
};

// Checks what expand_cycle needs; the same checks apply to a cycle a profile prints natively.
[[nodiscard]] CycleError check(const Cycle& cycle, const ExpandOptions& options = {}) noexcept;

// Emits the expansion above on `out`, or nothing and the reason when check() fails.
[[nodiscard]] CycleError expand_cycle(const Cycle& cycle, Sink& out,
                                      const ExpandOptions& options = {});

}  // namespace ncpost::canon
