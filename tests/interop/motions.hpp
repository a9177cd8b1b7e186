#pragma once
// The motion model shared by the interop tests: a posted program, read back by an interpreter
// (rs274) or by a dialect checker, must give the same motions as our canonical program. A
// motion is kept in rs274's terms (kind, numbers, feed in force) so that every reader produces
// the same shape and one comparison serves them all.

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::interop {

// Largest difference allowed between a motion read back and ours (program units, mm/min).
inline constexpr double kTolerance = 0.001;
// Largest difference allowed between the tool axes (unit vectors, per component) of a
// five-axis post read back through the forward kinematics and ours (docs/kinematics.md).
inline constexpr double kAxisTolerance = 1e-6;

// One motion: "STRAIGHT_TRAVERSE" or "STRAIGHT_FEED" with x y z, or "ARC_FEED" with rs274's
// first_end second_end first_axis second_axis rotation axis_end_point; and the feed rate in
// force (not compared for traverses).
struct Motion {
  std::string kind;
  std::vector<double> values;
  double feed = 0;
  // Where an arc ends in X Y Z (its values are in its plane's order), when the reader knows it.
  std::optional<canon::Point> end{};
  // Five-axis profiles: the tool axis in force at the motion's end (unit, program
  // coordinates); empty otherwise.
  std::vector<double> axis{};
};

[[nodiscard]] std::string describe(const Motion& m);

// How to turn the canonical program into the motions a profile's output should contain.
struct MotionOptions {
  // Cut NURBS into straight feeds with this chord tolerance (the renderer's linearisation).
  double chord_tolerance = 0.001;
  // Map every point through the profile's set-up transform (program → machine axes), for
  // dialects whose output is in machine axes.
  const xslt::SetupTransform* setup = nullptr;
  // > 0: arcs of more than one turn in the XY plane become equal pieces of at most this many
  // degrees (controllers without a turn count on G2/G3).
  double split_multi_turn_degrees = 0;
  // > 0: a NURBS becomes one "NURBS_FEED" motion whose values are this many points of the
  // curve (x y z each) at equal steps of the normalised parameter, for dialects that write
  // the spline itself: the posted spline, read back, is sampled the same way, which is
  // independent of how its knots are shifted or its weights scaled.
  int nurbs_samples = 0;
  // A five-axis profile's kinematics: every motion carries the tool axis in force (+Z at the
  // start). Ours (`posted` false): from the calls' tool axes. Posted (`posted` true): the
  // calls carry the machine's rotary positions and, without tool-centre-point control, its
  // linear positions; the tests' forward kinematics (tests/common/forward_kinematics.hpp)
  // turns them back into the tool tip and axis, with the tool length of the last
  // USE_TOOL_LENGTH_OFFSET.
  const profile::Kinematics* kinematics = nullptr;
  bool posted = false;
  // The profile's length unit in program units (pivots are in the profile's unit).
  double pivot_scale = 1.0;
};

// Our canonical program as motions: cycles expanded (canon::expand_cycle), NURBS linearised
// (or sampled, see nurbs_samples), the feed in force attached to each motion.
class Motions final : public canon::Sink {
 public:
  explicit Motions(MotionOptions options = {});
  void call(const canon::Call& call) override;
  std::vector<Motion> motions;

 private:
  [[nodiscard]] canon::Point map(canon::Point p) const;
  void add_arc(const canon::ArcFeed& arc);
  // Five-axis: the pose's tool axis (ours) or rotary positions (posted) taken into force, and
  // a posted point turned back into program coordinates.
  void follow_orientation(const canon::Pose& pose);
  [[nodiscard]] canon::Point program_point(const canon::Point& p) const;
  void push(Motion m);
  MotionOptions options_;
  canon::Point position_{};
  double feed_ = 0;
  std::vector<double> axis_{0, 0, 1};
  canon::Rotary rotary_{};
  double tool_length_ = 0;
};

// The default options for a profile: its chord tolerance, no set-up, no arc split.
[[nodiscard]] MotionOptions options_for(const profile::Profile& profile);

// `count` points of the curve at equal steps of the parameter over its knot range (count >= 2).
[[nodiscard]] std::vector<canon::Point> sample(const canon::NurbsFeed& nurbs, int count);

// Drops straight motions that end where they start (a dialect that positions before a cycle
// and then runs it repeats the position; a block that only sets a feed moves nowhere), and
// merges a traverse into the previous one when both are on one line in the same direction (a
// controller's cycle may retract in two steps where the canonical expansion takes one).
[[nodiscard]] std::vector<Motion> normalised(const std::vector<Motion>& motions);

// The motions without the straight ones that end where they start: a traverse to where the
// tool stands moves nothing (rs274 prints them for a G0 to the current position, and a
// canonical cycle's approach to an R level it already stands at). Motions start at the origin.
[[nodiscard]] std::vector<Motion> without_null_moves(const std::vector<Motion>& motions);

// Linearises a NURBS exactly as the Motions sink does (same tolerance → same points), for
// checkers that read a native spline back.
[[nodiscard]] std::vector<canon::Point> linearize(const canon::NurbsFeed& nurbs, double tolerance);

struct Outcome {
  std::size_t compared = 0;
  double max_deviation = 0;
  double max_axis_deviation = 0;  // five-axis: tool axes, per component
};

// What compare_motions found: the motions compared, the largest deviations, and each
// difference (a different count, a different kind — where the comparison stops —, a number or
// a feed beyond kTolerance, a tool axis beyond the axis tolerance or on one side only) as a
// message naming the other side.
struct Comparison {
  Outcome outcome;
  std::vector<std::string> differences;
  [[nodiscard]] bool same() const { return differences.empty(); }
};

// Compares motion by motion: kind, count, every number, the feed of feed motions unless
// `compare_feeds` is false (a program in inverse time or per revolution, whose feeds rs274
// prints as written while the canonical program has them per minute), and the tool axis of
// five-axis motions within `axis_tolerance`.
[[nodiscard]] Comparison compare_motions(const std::vector<Motion>& ours,
                                         const std::vector<Motion>& theirs, const std::string& who,
                                         bool compare_feeds = true,
                                         double axis_tolerance = kAxisTolerance);

// compare_motions (feeds compared), with a gtest failure for each difference.
Outcome expect_same_motions(const std::vector<Motion>& ours, const std::vector<Motion>& theirs,
                            const std::string& who, double axis_tolerance = kAxisTolerance);

// ---- LinuxCNC's rs274 -----------------------------------------------------------------------

inline constexpr const char* kRs274 = "/usr/bin/rs274";

// The motions of rs274's canonical output: lines "   30 N..... STRAIGHT_TRAVERSE(91.9000, ...)"
// (the counter may have been cut off, as the interpreter tests' `expected` files do), with the
// SET_FEED_RATE in force. NURBS_FEED, which rs274 prints without its numbers, becomes a motion
// of kind "NURBS_FEED" without values.
[[nodiscard]] std::vector<Motion> parse_rs274(const std::string& text);

// rs274's canonical output read into canonical calls, for the five-axis profiles (whose motions
// Motions turns back through the forward kinematics, MotionOptions::posted): feeds, planes,
// motions with their rotary axes A B C, and the tool length offset, with the length
// `tool_lengths` gives the tool in the spindle (the tool table rs274 reads has zero lengths:
// its positions are the programmed ones). Lengths and feeds are multiplied by `length_scale`
// (rs274 prints millimetres whatever the program's unit: 1/25.4 for an inch program).
[[nodiscard]] std::vector<canon::Call> parse_rs274_calls(
    const std::string& text, const std::map<int, double>& tool_lengths = {},
    double length_scale = 1.0);

struct Rs274Run {
  int status = -1;    // exit status of rs274 (0: the program was accepted)
  std::string canon;  // its canonical calls
  std::string log;    // what it wrote to stdout and stderr besides
};

// Runs `rs274 -g ARGS... PROGRAM CANON` in `dir` (it may write rs274ngc.var there). Callers
// hold the rs274 lock (ctest RESOURCE_LOCK rs274, or flock /tmp/ncpost-rs274.lock): LinuxCNC
// keeps the tool table in shared memory.
[[nodiscard]] Rs274Run run_rs274(const std::filesystem::path& dir,
                                 const std::filesystem::path& program,
                                 const std::vector<std::string>& args);

// An input file posted with one profile: the canonical program and the text.
struct Posted {
  std::shared_ptr<const profile::LoadedProfile> profile;
  std::vector<canon::Call> calls;
  std::string text;
  std::vector<diag::FileDiagnostic> render_diagnostics;
};

// Loads the built-in profile `profile_id`, interprets `input` (STEP-NC: ISO 14649, or AP238 AIM
// through engine/ap238) and renders it. Adds gtest failures for load, interpretation or (unless
// `expect_rendered` is false) rendering errors; `profile` is null when the profile does not load.
// `tolerant`: the schema check of a job without --strict (pipeline::LoadOptions::tolerant), for
// programs written the way other systems write them.
[[nodiscard]] Posted post_file(const std::filesystem::path& input, const std::string& profile_id,
                               bool expect_rendered = true, bool tolerant = false);

// The AP238 AIM programs every checker posts: the project's own (tests/golden/ap238/cases)
// and, when the corpus is there, its 17 milling programs of p21-aim/ (the two turning ones are
// refused and not posted).
[[nodiscard]] std::vector<std::filesystem::path> ap238_programs();
// Renders a canonical program (from any reader: the CL reader's, a hand-made one) with the
// built-in profile `profile_id`, with the same gtest failures.
[[nodiscard]] Posted post_calls(std::vector<canon::Call> calls, const std::string& profile_id,
                                bool expect_rendered = true);

// How a canonical program maps onto a dialect's output, for reading the output back: `ours`
// for the canonical program (the profile's set-up transform for dialects that write machine
// axes, multi-turn arcs cut where the dialect cuts them, splines sampled where it writes them),
// `theirs` for the calls read back (the text already has all that).
struct ReadBackOptions {
  MotionOptions ours;
  MotionOptions theirs;
};
inline constexpr int kNurbsSamples = 33;
[[nodiscard]] ReadBackOptions read_back_options(const std::string& profile_id,
                                                const profile::Profile& profile);

// None of the golden inputs has a drilling cycle: a hand-made canonical program with every
// kind (drill, drill with dwell, G83 with a 1 mm clearance, G73 with a 0.5 mm back-off back to
// R, ream, tap, bore with spindle stop).
[[nodiscard]] std::vector<canon::Call> cycles_program();

// A built-in profile, loaded once per test program (adds a failure when it does not load).
[[nodiscard]] std::shared_ptr<const profile::LoadedProfile> load_profile(const std::string& id);

// The motions of `calls` with `options`.
[[nodiscard]] std::vector<Motion> motions_of(const std::vector<canon::Call>& calls,
                                             const MotionOptions& options);

// A five-axis program by hand (for the five-axis profiles): tilts in every direction, the
// rotating axis twice past +-180 degrees, an arc and a NURBS with the tool tilted, back to the
// pole.
[[nodiscard]] std::vector<canon::Call> five_axis_program();

}  // namespace ncpost::interop
