#include "motions.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <regex>
#include <sstream>

#include "corpus.hpp"
#include "forward_kinematics.hpp"
#include "ncpost/ap238/ap238.hpp"
#include "ncpost/canon/cycle.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::interop {

std::string describe(const Motion& m) {
  std::ostringstream s;
  s << m.kind << "(";
  for (std::size_t i = 0; i < m.values.size(); ++i) s << (i ? ", " : "") << m.values[i];
  s << ") F" << m.feed;
  if (m.axis.size() == 3)
    s << " axis (" << m.axis[0] << ", " << m.axis[1] << ", " << m.axis[2] << ")";
  return s.str();
}

Motions::Motions(MotionOptions options) : options_(options) {}

canon::Point Motions::map(canon::Point p) const {
  if (!options_.setup) return p;
  const auto& m = options_.setup->matrix;
  const auto& t = options_.setup->translation;
  return {m[0] * p.x + m[1] * p.y + m[2] * p.z + t[0], m[3] * p.x + m[4] * p.y + m[5] * p.z + t[1],
          m[6] * p.x + m[7] * p.y + m[8] * p.z + t[2]};
}

void Motions::push(Motion m) {
  if (options_.kinematics) m.axis = axis_;
  motions.push_back(std::move(m));
}

void Motions::follow_orientation(const canon::Pose& pose) {
  if (!options_.kinematics) return;
  if (!options_.posted) {
    if (!pose.tool_axis) return;
    const auto& v = *pose.tool_axis;
    const double size = std::hypot(v.i, v.j, v.k);
    if (size > 0) axis_ = {v.i / size, v.j / size, v.k / size};
    return;
  }
  if (pose.rotary) rotary_ = *pose.rotary;
  const auto tool = test::forward(*options_.kinematics, {0, 0, 0}, rotary_, 0);
  axis_ = {tool.axis[0], tool.axis[1], tool.axis[2]};
}

canon::Point Motions::program_point(const canon::Point& p) const {
  if (!options_.kinematics || !options_.posted || options_.kinematics->tool_centre_point) return p;
  const auto tool = test::forward(*options_.kinematics, {p.x, p.y, p.z}, rotary_, tool_length_,
                                  options_.pivot_scale);
  return {tool.tip[0], tool.tip[1], tool.tip[2]};
}

void Motions::add_arc(const canon::ArcFeed& original) {
  canon::ArcFeed arc = original;
  follow_orientation(arc.end);
  if (options_.kinematics && options_.posted && !options_.kinematics->tool_centre_point) {
    // A posted arc in machine positions: its end, centre and normal back in the program's.
    const canon::Point end = program_point({arc.end.x, arc.end.y, arc.end.z});
    const canon::Point centre = program_point(arc.centre);
    const canon::Point tip = program_point(
        {arc.centre.x + arc.normal.i, arc.centre.y + arc.normal.j, arc.centre.z + arc.normal.k});
    arc.end.x = end.x;
    arc.end.y = end.y;
    arc.end.z = end.z;
    arc.centre = centre;
    arc.normal = {tip.x - centre.x, tip.y - centre.y, tip.z - centre.z};
  }
  if (options_.setup) {
    // A rotation keeps the turn count's sense relative to the (rotated) normal.
    const auto e = map({arc.end.x, arc.end.y, arc.end.z});
    const auto c = map(arc.centre);
    const auto& m = options_.setup->matrix;
    const auto& n = arc.normal;
    arc.end.x = e.x;
    arc.end.y = e.y;
    arc.end.z = e.z;
    arc.centre = c;
    arc.normal = {m[0] * n.i + m[1] * n.j + m[2] * n.k, m[3] * n.i + m[4] * n.j + m[5] * n.k,
                  m[6] * n.i + m[7] * n.j + m[8] * n.k};
  }
  const auto p = canon::plane_arc(arc);
  ASSERT_TRUE(p) << "tilted arc";
  const canon::Point end{arc.end.x, arc.end.y, arc.end.z};
  if (options_.split_multi_turn_degrees > 0 && p->plane == canon::Plane::Xy &&
      std::abs(p->rotation) > 1) {
    // Equal pieces by angle, Z linear in the angle: the helix itself, cut.
    const double cx = p->first_axis;
    const double cy = p->second_axis;
    const double r = std::hypot(position_.x - cx, position_.y - cy);
    const double a0 = std::atan2(position_.y - cy, position_.x - cx);
    const double a1 = std::atan2(end.y - cy, end.x - cx);
    double d = p->rotation > 0 ? a1 - a0 : a0 - a1;
    constexpr double kTwoPi = 2 * std::numbers::pi;
    while (d <= 1e-9) d += kTwoPi;
    while (d > kTwoPi + 1e-9) d -= kTwoPi;
    const double sweep = (d + kTwoPi * (std::abs(p->rotation) - 1)) * (p->rotation > 0 ? 1 : -1);
    const double limit = options_.split_multi_turn_degrees * std::numbers::pi / 180;
    const auto pieces = static_cast<int>(std::ceil(std::abs(sweep) / limit - 1e-9));
    const double z0 = position_.z;
    for (int k = 1; k <= pieces; ++k) {
      const double t = double(k) / double(pieces);
      const double angle = a0 + sweep * t;
      const canon::Point q = k == pieces
                                 ? end
                                 : canon::Point{cx + r * std::cos(angle), cy + r * std::sin(angle),
                                                z0 + (end.z - z0) * t};
      push({"ARC_FEED", {q.x, q.y, cx, cy, double(p->rotation > 0 ? 1 : -1), q.z}, feed_, q});
    }
  } else {
    push({"ARC_FEED",
          {p->first_end, p->second_end, p->first_axis, p->second_axis, double(p->rotation),
           p->axis_end_point},
          feed_,
          end});
  }
  position_ = end;
}

void Motions::call(const canon::Call& call) {
  if (const auto* f = std::get_if<canon::SetFeedRate>(&call)) feed_ = f->rate;
  if (const auto* l = std::get_if<canon::UseToolLengthOffset>(&call)) tool_length_ = l->length;
  if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
    follow_orientation(t->to);
    position_ = map(program_point({t->to.x, t->to.y, t->to.z}));
    push({"STRAIGHT_TRAVERSE", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* t = std::get_if<canon::StraightFeed>(&call)) {
    follow_orientation(t->to);
    position_ = map(program_point({t->to.x, t->to.y, t->to.z}));
    push({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* a = std::get_if<canon::ArcFeed>(&call)) add_arc(*a);
  const auto* original = std::get_if<canon::NurbsFeed>(&call);
  std::optional<canon::NurbsFeed> n;
  if (original) {
    n = *original;
    canon::Pose end{};
    end.rotary = n->rotary;
    end.tool_axis = n->tool_axis;
    follow_orientation(end);
    for (auto& q : n->points) {
      const canon::Point p = program_point({q.x, q.y, q.z});
      q.x = p.x;
      q.y = p.y;
      q.z = p.z;
    }
  }
  if (n && options_.nurbs_samples > 0) {
    Motion m{"NURBS_FEED", {}, feed_};
    for (const auto& q : sample(*n, options_.nurbs_samples)) {
      position_ = map(q);
      m.values.insert(m.values.end(), {position_.x, position_.y, position_.z});
    }
    push(std::move(m));
  } else if (n) {
    for (const auto& q : linearize(*n, options_.chord_tolerance)) {
      position_ = map(q);
      push({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
    }
  }
  // The expansion is a program of its own (its feed included); the feed in force after it is
  // the expansion's last, as for a controller running the cycle.
  if (const auto* c = std::get_if<canon::Cycle>(&call)) (void)canon::expand_cycle(*c, *this);
}

MotionOptions options_for(const profile::Profile& profile) {
  MotionOptions o;
  o.chord_tolerance = profile.chord_tolerance;
  if (profile.kinematics) o.kinematics = &*profile.kinematics;
  return o;
}

std::vector<canon::Point> sample(const canon::NurbsFeed& nurbs, int count) {
  std::vector<canon::Point> out;
  if (nurbs.knots.size() < 2 || count < 2) return out;
  const double u0 = nurbs.knots[static_cast<std::size_t>(nurbs.degree)];
  const double u1 = nurbs.knots[nurbs.knots.size() - 1 - static_cast<std::size_t>(nurbs.degree)];
  for (int k = 0; k < count; ++k)
    out.push_back(render::nurbs_point(nurbs, u0 + (u1 - u0) * double(k) / double(count - 1)));
  return out;
}

namespace {
bool same_direction(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9) return false;
  return true;
}
}  // namespace

std::vector<Motion> normalised(const std::vector<Motion>& motions) {
  std::vector<Motion> out;
  // Where the last kept motion ends and where the last kept traverse starts, when known.
  canon::Point at{}, from{};
  bool known_at = false, known_from = false;
  for (const auto& m : motions) {
    const bool straight = m.kind == "STRAIGHT_TRAVERSE" || m.kind == "STRAIGHT_FEED";
    if (!straight) {
      out.push_back(m);
      known_at = known_from = false;
      continue;
    }
    const canon::Point to{m.values[0], m.values[1], m.values[2]};
    // A five-axis motion that only turns the tool is a motion.
    const bool same_axis = known_at && same_direction(m.axis, out.back().axis);
    if (known_at && to == at && same_axis) continue;
    if (m.kind == "STRAIGHT_TRAVERSE" && known_from && known_at && same_axis &&
        out.back().kind == "STRAIGHT_TRAVERSE") {
      const double ax = at.x - from.x, ay = at.y - from.y, az = at.z - from.z;
      const double bx = to.x - at.x, by = to.y - at.y, bz = to.z - at.z;
      const double cross = std::hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx);
      const double dot = ax * bx + ay * by + az * bz;
      if (dot > 0 && cross <= 1e-9 * std::hypot(ax, ay, az) * std::hypot(bx, by, bz)) {
        out.back().values = m.values;
        at = to;
        continue;
      }
    }
    from = at;
    known_from = known_at;
    out.push_back(m);
    at = to;
    known_at = true;
  }
  return out;
}

std::vector<Motion> without_null_moves(const std::vector<Motion>& motions) {
  std::vector<Motion> out;
  // Both LinuxCNC and the converter start at the origin.
  std::optional<canon::Point> at = canon::Point{0, 0, 0};
  for (const auto& m : motions) {
    const bool straight = m.kind == "STRAIGHT_TRAVERSE" || m.kind == "STRAIGHT_FEED";
    if (!straight) {
      out.push_back(m);
      at = m.end;  // unknown when the reader did not say
      continue;
    }
    const canon::Point to{m.values[0], m.values[1], m.values[2]};
    if (at && std::abs(at->x - to.x) < 1e-12 && std::abs(at->y - to.y) < 1e-12 &&
        std::abs(at->z - to.z) < 1e-12)
      continue;
    at = to;
    out.push_back(m);
  }
  return out;
}

std::vector<canon::Point> linearize(const canon::NurbsFeed& nurbs, double tolerance) {
  return render::linearize(nurbs, tolerance);
}

Comparison compare_motions(const std::vector<Motion>& ours, const std::vector<Motion>& theirs,
                           const std::string& who, bool compare_feeds, double axis_tolerance) {
  Comparison c;
  if (ours.size() != theirs.size())
    c.differences.push_back("motion count: ours " + std::to_string(ours.size()) + ", " + who + " " +
                            std::to_string(theirs.size()));
  const std::size_t n = std::min(ours.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = ours[i];
    const auto& b = theirs[i];
    if (a.kind != b.kind || a.values.size() != b.values.size()) {
      c.differences.push_back("motion " + std::to_string(i) + ": ours " + describe(a) + ", " + who +
                              " " + describe(b));
      c.outcome.compared = i;
      return c;
    }
    double dev = 0;
    if (a.kind != "STRAIGHT_TRAVERSE" && compare_feeds) {
      dev = std::abs(a.feed - b.feed);
      if (dev > kTolerance)
        c.differences.push_back("feed of motion " + std::to_string(i) + ": ours " + describe(a) +
                                ", " + who + " " + describe(b));
    }
    double position = 0;
    for (std::size_t k = 0; k < a.values.size(); ++k)
      position = std::max(position, std::abs(a.values[k] - b.values[k]));
    if (position > kTolerance)
      c.differences.push_back("motion " + std::to_string(i) + ": ours " + describe(a) + ", " + who +
                              " " + describe(b));
    c.outcome.max_deviation = std::max({c.outcome.max_deviation, dev, position});
    if (a.axis.size() != b.axis.size()) {
      c.differences.push_back("motion " + std::to_string(i) +
                              ": a tool axis on one side only: ours " + describe(a) + ", " + who +
                              " " + describe(b));
      continue;
    }
    double axis_dev = 0;
    for (std::size_t k = 0; k < a.axis.size(); ++k)
      axis_dev = std::max(axis_dev, std::abs(a.axis[k] - b.axis[k]));
    if (axis_dev > axis_tolerance)
      c.differences.push_back("tool axis of motion " + std::to_string(i) + ": ours " + describe(a) +
                              ", " + who + " " + describe(b));
    c.outcome.max_axis_deviation = std::max(c.outcome.max_axis_deviation, axis_dev);
  }
  c.outcome.compared = n;
  return c;
}

Outcome expect_same_motions(const std::vector<Motion>& ours, const std::vector<Motion>& theirs,
                            const std::string& who, double axis_tolerance) {
  const Comparison c = compare_motions(ours, theirs, who, true, axis_tolerance);
  for (const auto& d : c.differences) ADD_FAILURE() << d;
  return c.outcome;
}

namespace {

// Calls `each(name, arguments, numbers)` for every call line of rs274's canonical output.
template <class Each>
void for_each_rs274_call(const std::string& text, Each&& each) {
  static const std::regex line(R"(^\s*(?:\d+\s+)?N(?:\.\.\.\.\.|\d+)\s+([A-Z_0-9]+)\((.*)\)\s*$)");
  std::istringstream in(text);
  std::string s;
  while (std::getline(in, s)) {
    std::smatch m;
    if (!std::regex_match(s, m, line)) continue;
    const std::string name = m[1];
    const std::string arguments = m[2];
    std::vector<double> numbers;
    std::string number;
    std::istringstream a(arguments);
    while (std::getline(a, number, ',')) numbers.push_back(std::strtod(number.c_str(), nullptr));
    each(name, arguments, numbers);
  }
}

}  // namespace

std::vector<Motion> parse_rs274(const std::string& text) {
  std::vector<Motion> out;
  double feed = 0;
  std::string plane = "CANON_PLANE_XY";
  for_each_rs274_call(text, [&](const std::string& name, const std::string& arguments,
                                std::vector<double> args) {
    if (name == "SELECT_PLANE") plane = arguments;
    if (name == "SET_FEED_RATE" && !args.empty()) feed = args[0];
    if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") {
      args.resize(3);  // x, y, z; a, b, c are read by parse_rs274_calls for those that need them
      out.push_back({name, args, feed});
    } else if (name == "ARC_FEED") {
      args.resize(6);  // first_end, second_end, first_axis, second_axis, rotation, axis_end_point
      // rs274's plane order: XY (x, y; z), XZ (z, x; y), YZ (y, z; x).
      const canon::Point end = plane == "CANON_PLANE_XZ" ? canon::Point{args[1], args[5], args[0]}
                               : plane == "CANON_PLANE_YZ"
                                   ? canon::Point{args[5], args[0], args[1]}
                                   : canon::Point{args[0], args[1], args[5]};
      out.push_back({name, args, feed, end});
    } else if (name == "NURBS_FEED") {
      out.push_back({name, {}, feed});
    }
  });
  return out;
}

std::vector<canon::Call> parse_rs274_calls(const std::string& text,
                                           const std::map<int, double>& tool_lengths,
                                           double length_scale) {
  std::vector<canon::Call> out;
  canon::Plane plane = canon::Plane::Xy;
  int selected = 0, tool = 0;
  for_each_rs274_call(text, [&](const std::string& name, const std::string& arguments,
                                const std::vector<double>& args) {
    const auto rotary = [&](std::size_t first) {
      return canon::Rotary{args[first], args[first + 1], args[first + 2]};
    };
    if (name == "SET_FEED_RATE" && !args.empty())
      out.emplace_back(canon::SetFeedRate{args[0] * length_scale});
    if (name == "SELECT_PLANE")
      plane = arguments.find("YZ") != std::string::npos   ? canon::Plane::Yz
              : arguments.find("XZ") != std::string::npos ? canon::Plane::Xz
                                                          : canon::Plane::Xy;
    // SELECT_TOOL names the tool; CHANGE_TOOL prints its index in the tool table.
    if (name == "SELECT_TOOL" && !args.empty()) selected = static_cast<int>(args[0]);
    if (name == "CHANGE_TOOL") tool = selected;
    if (name == "USE_TOOL_LENGTH_OFFSET") {
      const auto length = tool_lengths.find(tool);
      out.emplace_back(
          canon::UseToolLengthOffset{length != tool_lengths.end() ? length->second : 0.0});
    }
    if ((name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") && args.size() >= 6) {
      const canon::Pose to{args[0] * length_scale, args[1] * length_scale, args[2] * length_scale,
                           rotary(3), std::nullopt};
      if (name == "STRAIGHT_TRAVERSE")
        out.emplace_back(canon::StraightTraverse{to});
      else
        out.emplace_back(canon::StraightFeed{to});
    } else if (name == "ARC_FEED" && args.size() >= 9) {
      // first_end, second_end, first_axis, second_axis, rotation, axis_end_point, a, b, c
      canon::ArcFeed arc = canon::arc_from_plane(
          {plane, args[0] * length_scale, args[1] * length_scale, args[2] * length_scale,
           args[3] * length_scale, static_cast<int>(args[4]), args[5] * length_scale});
      arc.end.rotary = rotary(6);
      out.emplace_back(arc);
    }
  });
  return out;
}

Rs274Run run_rs274(const std::filesystem::path& dir, const std::filesystem::path& program,
                   const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  Rs274Run run;
  const fs::path work = fs::temp_directory_path() / ("ncpost-rs274-" + std::to_string(::getpid()) +
                                                     "-" + std::to_string(::rand()));
  fs::create_directories(work);
  // A program that loops for ever must not hang the test: rs274 gets two minutes.
  std::string command = "cd '" + dir.string() + "' && timeout 120 " + kRs274 + " -g";
  for (const auto& a : args) command += " '" + a + "'";
  command += " '" + program.string() + "' '" + (work / "canon.txt").string() + "' > '" +
             (work / "rs274.log").string() + "' 2>&1 < /dev/null";
  const int rc = std::system(command.c_str());
  run.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  run.canon = test::read_file(work / "canon.txt");
  run.log = test::read_file(work / "rs274.log");
  std::error_code ec;
  fs::remove_all(work, ec);
  return run;
}

namespace {

std::shared_ptr<const profile::LoadedProfile> builtin_profile(const std::string& profile_id) {
  xslt::initialise();
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  auto loaded = store.load(profile_id, diagnostics);
  EXPECT_TRUE(loaded) << profile_id << ": "
                      << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  return loaded;
}

}  // namespace

Posted post_calls(std::vector<canon::Call> calls, const std::string& profile_id,
                  bool expect_rendered) {
  Posted posted;
  posted.profile = builtin_profile(profile_id);
  if (!posted.profile) return posted;
  posted.calls = std::move(calls);
  posted.text = render::render_program(*posted.profile, posted.calls, posted.render_diagnostics);
  if (expect_rendered) {
    EXPECT_FALSE(diag::has_errors(posted.render_diagnostics))
        << profile_id << ": " << diag::format(posted.render_diagnostics.front());
  }
  return posted;
}

Posted post_file(const std::filesystem::path& input, const std::string& profile_id,
                 bool expect_rendered, bool tolerant) {
  static const express::SchemaRegistry registry;
  pipeline::LoadOptions load_options;
  load_options.tolerant = tolerant;
  auto loaded = pipeline::load(test::read_file(input), registry, load_options);
  EXPECT_TRUE(loaded.ok()) << input;
  if (!loaded.ok()) return {builtin_profile(profile_id), {}, {}, {}};
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  // AP238 AIM programs through engine/ap238, as the pipeline takes them (docs/ap238.md).
  const auto interpreted = ap238::is_aim(loaded.model)
                               ? ap238::interpret(loaded.model, attributes, buffer, {})
                               : stepnc::interpret(loaded.model, attributes, buffer, {});
  EXPECT_TRUE(interpreted.ok()) << input;
  return post_calls(std::move(buffer).take(), profile_id, expect_rendered);
}

std::vector<std::filesystem::path> ap238_programs() {
  std::vector<std::filesystem::path> out;
  const auto own = test::source_dir() / "tests" / "golden" / "ap238" / "cases";
  for (const char* name : {"own-mill-mm.aim.stp", "own-mill-inch.aim.stp"})
    out.push_back(own / name);
  if (const auto corpus = test::corpus_dir()) {
    std::vector<std::filesystem::path> milling;
    for (const auto& e : std::filesystem::directory_iterator(*corpus / "p21-aim")) {
      const std::string stem = e.path().stem().string();
      if (e.path().extension() == ".stpnc" && stem != "nextnc_autodesk-face" &&
          stem != "nextnc_autodesk-profile")  // the two turning programs, refused
        milling.push_back(e.path());
    }
    std::sort(milling.begin(), milling.end());
    out.insert(out.end(), milling.begin(), milling.end());
  }
  return out;
}

std::vector<Motion> motions_of(const std::vector<canon::Call>& calls,
                               const MotionOptions& options) {
  Motions m(options);
  for (const auto& c : calls) m.call(c);
  return std::move(m.motions);
}

ReadBackOptions read_back_options(const std::string& profile_id, const profile::Profile& p) {
  ReadBackOptions c{options_for(p), options_for(p)};
  c.theirs.posted = true;  // five-axis: rotary (and machine) positions, turned back
  if (p.nurbs == profile::NurbsMode::Native) {
    c.ours.nurbs_samples = kNurbsSamples;
    c.theirs.nurbs_samples = kNurbsSamples;
  }
  if (profile_id == "hnc-21" || profile_id == "okuma-osp") c.ours.split_multi_turn_degrees = 180;
  if (profile_id == "hnc-21") c.ours.setup = &p.setup;
  return c;
}

std::vector<canon::Call> cycles_program() {
  std::vector<canon::Call> calls;
  calls.emplace_back(canon::Begin{canon::Scope::Project, {1, "PROJECT", "CYCLES"}});
  calls.emplace_back(canon::UseLengthUnits{canon::Units::Millimetres});
  calls.emplace_back(canon::SelectPlane{canon::Plane::Xy});
  calls.emplace_back(
      canon::Begin{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "HOLES"}});
  calls.emplace_back(canon::SelectTool{3});
  calls.emplace_back(canon::ChangeTool{3});
  calls.emplace_back(canon::UseToolLengthOffset{80});
  calls.emplace_back(canon::SetFeedRate{400});
  calls.emplace_back(canon::SetSpindleSpeed{1200});
  calls.emplace_back(canon::StartSpindleClockwise{});
  calls.emplace_back(canon::FloodOn{});
  calls.emplace_back(canon::StraightTraverse{{0, 0, 50}});
  canon::Cycle c;
  c.x = 10;
  c.y = 20;
  c.safe_z = 50;
  c.r_z = 2;
  c.bottom_z = -15;
  c.feed = 150;
  calls.emplace_back(c);  // G81
  c.x = 30;
  c.dwell = 0.5;
  calls.emplace_back(c);  // G82
  c.kind = canon::CycleKind::PeckDrill;
  c.x = 50;
  c.dwell = 0;
  c.peck = 6;
  c.peck_clearance = 1.0;
  calls.emplace_back(c);  // G83
  c.x = 70;
  c.peck_clearance = 0;
  c.peck_retract = 0.5;
  c.safe_z = 2;           // back to the R plane (G99)
  calls.emplace_back(c);  // G73
  c = canon::Cycle{};
  c.kind = canon::CycleKind::Ream;
  c.x = 90;
  c.y = 20;
  c.safe_z = 50;
  c.r_z = 2;
  c.bottom_z = -12;
  c.feed = 120;
  calls.emplace_back(c);  // G85
  c.kind = canon::CycleKind::Tap;
  c.x = 110;
  c.pitch = 1.5;
  c.spindle_speed = 300;
  c.feed = 450;
  calls.emplace_back(c);  // G84
  c.kind = canon::CycleKind::Bore;
  c.x = 130;
  c.spindle_stop = true;
  c.feed = 100;
  calls.emplace_back(c);  // G86
  calls.emplace_back(canon::SetFeedRate{300});
  calls.emplace_back(canon::StraightFeed{{130, 40, 50}});
  calls.emplace_back(canon::End{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "HOLES"}});
  calls.emplace_back(canon::StopSpindleTurning{});
  calls.emplace_back(canon::FloodOff{});
  calls.emplace_back(canon::ProgramEnd{});
  calls.emplace_back(canon::End{canon::Scope::Project, {1, "PROJECT", "CYCLES"}});
  return calls;
}

std::shared_ptr<const profile::LoadedProfile> load_profile(const std::string& id) {
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  xslt::initialise();
  std::vector<diag::FileDiagnostic> diagnostics;
  auto p = store.load(id, diagnostics);
  EXPECT_TRUE(p) << id;
  return p;
}

// A five-axis program by hand: tilts in every direction, a wrap of the rotating axis, an arc
// and a NURBS with the tool tilted (they keep the orientation in force), and back to the pole.
std::vector<canon::Call> five_axis_program() {
  using canon::Direction;
  std::vector<canon::Call> calls;
  calls.emplace_back(canon::Begin{canon::Scope::Project, {1, "PROJECT", "FIVE"}});
  calls.emplace_back(canon::UseLengthUnits{canon::Units::Millimetres});
  calls.emplace_back(canon::SelectPlane{canon::Plane::Xy});
  calls.emplace_back(canon::Begin{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "5X"}});
  calls.emplace_back(canon::SelectTool{4});
  calls.emplace_back(canon::ChangeTool{4});
  calls.emplace_back(canon::UseToolLengthOffset{82.5});
  calls.emplace_back(canon::SetSpindleSpeed{9000});
  calls.emplace_back(canon::StartSpindleClockwise{});
  calls.emplace_back(canon::StraightTraverse{{0, 0, 60}});
  calls.emplace_back(canon::SetFeedRate{800});
  const double s = std::sin(25 * std::numbers::pi / 180), c = std::cos(25 * std::numbers::pi / 180);
  const auto feed = [&](double x, double y, double z, Direction d) {
    calls.emplace_back(canon::StraightFeed{{x, y, z, std::nullopt, d}});
  };
  feed(0, 0, 10, {0, 0, 1});
  for (int step = 0; step <= 8; ++step) {  // round Z in eighths of a turn, twice past +-180
    const double a = step * std::numbers::pi / 4;
    feed(10 * std::cos(a), 10 * std::sin(a), 5 - 0.5 * step, {s * std::cos(a), s * std::sin(a), c});
  }
  // An arc and a NURBS with the tool at 25 degrees towards +X (both keep it).
  feed(20, 0, 0, {s, 0, c});
  canon::ArcFeed arc;
  arc.end = {30, 10, 0};
  arc.centre = {30, 0, 0};
  arc.normal = {0, 0, 1};
  arc.turns = 1;
  calls.emplace_back(arc);
  canon::NurbsFeed nurbs;
  nurbs.degree = 2;
  nurbs.points = {{30, 10, 0, 1}, {30, 20, 0, 0.8}, {40, 20, -2, 1}};
  nurbs.knots = {0, 0, 0, 1, 1, 1};
  nurbs.tool_axis = Direction{s, 0, c};
  calls.emplace_back(nurbs);
  // A slanted line and back to the pole.
  feed(50, 20, -2, {-0.3, 0.4, std::sqrt(1 - 0.25)});
  feed(50, 20, 20, {0, 0, 1});
  calls.emplace_back(canon::StraightTraverse{{50, 20, 60}});
  calls.emplace_back(canon::End{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "5X"}});
  calls.emplace_back(canon::StopSpindleTurning{});
  calls.emplace_back(canon::ProgramEnd{});
  calls.emplace_back(canon::End{canon::Scope::Project, {1, "PROJECT", "FIVE"}});
  return calls;
}

}  // namespace ncpost::interop
