// Robot dialect checkers: what the kuka-krl and abb-rapid profiles write is read back (PTP / LIN
// / CIRC with the auxiliary point, MoveJ / MoveL / MoveC with inline robtargets, the path
// velocity in force) into motions and compared with our canonical program through motions.hpp.
// A circle through start, auxiliary point and end gives the centre back; the feed comes back
// from m/s (KRL) or mm/s (RAPID). The robot form of our program is modelled here: plane arcs in
// equal pieces of at most 180 degrees (one CIRC / MoveC each), helices as straight points
// within the stylesheets' chord deviation (a robot circle is planar). No external program.

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/render/render.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The stylesheets' chord deviation for helices (mm) and largest CIRC / MoveC piece (degrees).
constexpr double kChord = 0.001;
constexpr double kMaxPiece = 180;

// rs274 plane coordinates (first, second, axis) of a point, and back.
Vec to_plane(const Vec& p, int plane) {  // 0 xy, 1 yz, 2 xz
  if (plane == 1) return {p[1], p[2], p[0]};
  if (plane == 2) return {p[2], p[0], p[1]};
  return p;
}
Vec from_plane(const Vec& q, int plane) {
  if (plane == 1) return {q[2], q[0], q[1]};
  if (plane == 2) return {q[1], q[2], q[0]};
  return q;
}

// Our canonical motions in the robots' form: each arc of `ours` (rs274 values, see
// motions.hpp) cut as the stylesheets cut it. `plane_of_arc` is the plane of each arc in
// order (the Motion keeps only the rs274 numbers).
std::vector<Motion> robot_form(const std::vector<Motion>& ours, const std::vector<int>& planes) {
  std::vector<Motion> out;
  Vec at{0, 0, 0};
  std::size_t arc_index = 0;
  for (const auto& m : ours) {
    if (m.kind != "ARC_FEED") {
      out.push_back(m);
      at = {m.values[0], m.values[1], m.values[2]};
      continue;
    }
    const int plane = planes.at(arc_index++);
    const Vec s = to_plane(at, plane);
    const double ef = m.values[0], es = m.values[1], cf = m.values[2], cs = m.values[3];
    const double rotation = m.values[4], ea = m.values[5];
    const double r = std::hypot(s[0] - cf, s[1] - cs);
    const double a0 = std::atan2(s[1] - cs, s[0] - cf);
    const double a1 = std::atan2(es - cs, ef - cf);
    constexpr double kTwoPi = 2 * std::numbers::pi;
    double d = rotation > 0 ? a1 - a0 : a0 - a1;
    while (d <= 1e-9) d += kTwoPi;
    while (d > kTwoPi + 1e-9) d -= kTwoPi;
    const double sweep_deg = (d + kTwoPi * (std::abs(rotation) - 1)) * 180 / std::numbers::pi;
    const bool helix = std::abs(ea - s[2]) > 1e-9;
    const double step =
        !helix ? kMaxPiece
               : (r <= 2 * kChord ? 90 : 2 * std::acos(1 - kChord / r) * 180 / std::numbers::pi);
    const int pieces = std::max(1, static_cast<int>(std::ceil(sweep_deg / step - 1e-9)));
    const double sign = rotation > 0 ? 1 : -1;
    for (int k = 1; k <= pieces; ++k) {
      const double t = double(k) / pieces;
      const double angle = a0 + sign * sweep_deg * std::numbers::pi / 180 * t;
      const Vec q = k == pieces ? Vec{ef, es, ea}
                                : Vec{cf + r * std::cos(angle), cs + r * std::sin(angle),
                                      s[2] + (ea - s[2]) * t};
      if (helix) {
        const Vec p = from_plane(q, plane);
        out.push_back({"STRAIGHT_FEED", {p[0], p[1], p[2]}, m.feed});
      } else {
        out.push_back({"ARC_FEED", {q[0], q[1], cf, cs, sign, q[2]}, m.feed});
      }
    }
    at = from_plane({ef, es, ea}, plane);
  }
  return out;
}

// The plane (0 xy, 1 yz, 2 xz) of every arc of `calls`, in order.
std::vector<int> arc_planes(const std::vector<canon::Call>& calls) {
  std::vector<int> planes;
  for (const auto& c : calls)
    if (const auto* a = std::get_if<canon::ArcFeed>(&c)) {
      const auto p = canon::plane_arc(*a);
      planes.push_back(!p                             ? 0
                       : p->plane == canon::Plane::Yz ? 1
                       : p->plane == canon::Plane::Xz ? 2
                                                      : 0);
    }
  return planes;
}

// One CIRC / MoveC read back: the circle through start, aux and end, in rs274 terms.
Motion circle(const Vec& start, const Vec& aux, const Vec& end, double feed) {
  const Vec u = sub(aux, start), v = sub(end, start);
  const Vec w = cross(u, v);
  const double ww = dot(w, w);
  if (ww == 0) return {"ARC_FEED(collinear)", {}, feed};
  const Vec a = cross(v, w), b = cross(w, u);
  const double uu = dot(u, u), vv = dot(v, v);
  const Vec centre{start[0] + (uu * a[0] + vv * b[0]) / (2 * ww),
                   start[1] + (uu * a[1] + vv * b[1]) / (2 * ww),
                   start[2] + (uu * a[2] + vv * b[2]) / (2 * ww)};
  // Sense of travel: start → aux → end turns about n = (aux - start) x (end - aux).
  const Vec n = cross(u, sub(end, aux));
  int plane = 0;
  if (std::abs(n[0]) > std::abs(n[1]) && std::abs(n[0]) > std::abs(n[2])) plane = 1;
  if (std::abs(n[1]) > std::abs(n[0]) && std::abs(n[1]) > std::abs(n[2])) plane = 2;
  const double sense = n[plane == 0 ? 2 : plane == 1 ? 0 : 1] > 0 ? 1 : -1;
  const Vec e = to_plane(end, plane), c = to_plane(centre, plane);
  return {"ARC_FEED", {e[0], e[1], c[0], c[1], sense, e[2]}, feed};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(line);
  }
  return out;
}

std::optional<double> number_after(const std::string& text, const std::string& name) {
  const auto at = text.find(name);
  if (at == std::string::npos) return std::nullopt;
  return std::stod(text.substr(at + name.size()));
}

// "{X 1, Y 2, Z 3, A 0, B 0, C 180}" frames of a KRL line, in order.
std::vector<Vec> krl_frames(const std::string& line) {
  std::vector<Vec> out;
  static const std::regex frame(R"(\{X ([-0-9.eE]+), Y ([-0-9.eE]+), Z ([-0-9.eE]+), A)");
  for (auto it = std::sregex_iterator(line.begin(), line.end(), frame);
       it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
  return out;
}

// KRL: `V_FEED = v` (m/s), `$VEL.CP = V_RAPID | V_FEED` (the value is copied when assigned, as
// KRL assigns), PTP / LIN / CIRC. `errors` collects what the reader does not understand.
std::vector<Motion> read_krl(const std::string& text, std::vector<std::string>& errors) {
  std::vector<Motion> out;
  double v_feed = 0, vel = 0;
  bool rapid = true;
  Vec at{0, 0, 0};
  for (const auto& raw : lines_of(text)) {
    const std::string line = raw.substr(0, raw.find(';'));
    if (line.rfind("V_FEED = ", 0) == 0) v_feed = *number_after(line, "V_FEED = ") * 60000;
    if (line == "$VEL.CP = V_RAPID") rapid = true;
    if (line == "$VEL.CP = V_FEED") {
      rapid = false;
      vel = v_feed;
    }
    const auto frames = krl_frames(line);
    if (line.rfind("PTP ", 0) == 0 || line.rfind("LIN ", 0) == 0) {
      if (frames.size() != 1) {
        errors.push_back("bad motion: " + line);
        continue;
      }
      at = frames[0];
      const bool traverse = line.rfind("PTP ", 0) == 0 || rapid;
      out.push_back({traverse ? "STRAIGHT_TRAVERSE" : "STRAIGHT_FEED", {at[0], at[1], at[2]}, vel});
    } else if (line.rfind("CIRC ", 0) == 0) {
      if (frames.size() != 2 || rapid) {
        errors.push_back("bad CIRC (two frames, at feed velocity): " + line);
        continue;
      }
      out.push_back(circle(at, frames[0], frames[1], vel));
      at = frames[1];
    }
  }
  return out;
}

// RAPID: `vFeed.v_tcp := v;` (mm/s), MoveJ / MoveL / MoveC with inline robtargets and the
// speeddata vRapid or vFeed (passed by value when the move is called).
std::vector<Motion> read_rapid(const std::string& text, std::vector<std::string>& errors) {
  std::vector<Motion> out;
  double v_feed = 0;
  Vec at{0, 0, 0};
  static const std::regex target(R"(\[\[([-0-9.eE]+),([-0-9.eE]+),([-0-9.eE]+)\],)");
  for (const auto& raw : lines_of(text)) {
    const auto first = raw.find_first_not_of(' ');
    if (first == std::string::npos) continue;
    const std::string line = raw.substr(
        first, raw.find('!') == std::string::npos ? std::string::npos : raw.find('!') - first);
    if (line.rfind("vFeed.v_tcp := ", 0) == 0) v_feed = *number_after(line, "vFeed.v_tcp := ") * 60;
    const bool j = line.rfind("MoveJ ", 0) == 0, l = line.rfind("MoveL ", 0) == 0,
               c = line.rfind("MoveC ", 0) == 0;
    if (!j && !l && !c) continue;
    std::vector<Vec> targets;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), target);
         it != std::sregex_iterator(); ++it)
      targets.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
    const bool rapid = line.find(", vRapid, ") != std::string::npos;
    const bool feed = line.find(", vFeed, ") != std::string::npos;
    if (targets.size() != (c ? 2u : 1u) || rapid == feed || (c && rapid)) {
      errors.push_back("bad move: " + line);
      continue;
    }
    if (c) {
      out.push_back(circle(at, targets[0], targets[1], v_feed));
      at = targets[1];
    } else {
      at = targets[0];
      out.push_back(
          {j || rapid ? "STRAIGHT_TRAVERSE" : "STRAIGHT_FEED", {at[0], at[1], at[2]}, v_feed});
    }
  }
  return out;
}

using Reader = std::vector<Motion> (*)(const std::string&, std::vector<std::string>&);

std::vector<fs::path> cases() {
  const fs::path dir = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  std::vector<fs::path> out{dir / "curves.stp", dir / "executables.stp",
                            dir / "placement-rotated-setup.stp"};
  if (const auto corpus = test::corpus_dir())
    out.push_back(*corpus / "p21" / "nist_toolkit_ex1E.stp");
  const auto aim = ap238_programs();  // AP238 AIM programs through engine/ap238
  out.insert(out.end(), aim.begin(), aim.end());
  return out;
}

void check(const std::string& profile_id, Reader read) {
  std::size_t arcs = 0, compared = 0;
  for (const auto& input : cases()) {
    SCOPED_TRACE(profile_id + " " + input.filename().string());
    const Posted posted = post_file(input, profile_id);
    ASSERT_TRUE(posted.profile);
    const auto ours = robot_form(motions_of(posted.calls, options_for(posted.profile->profile)),
                                 arc_planes(posted.calls));
    std::vector<std::string> errors;
    const auto theirs = read(posted.text, errors);
    for (const auto& e : errors) ADD_FAILURE() << e;
    for (const auto& m : theirs) arcs += m.kind == "ARC_FEED";
    const Outcome o = expect_same_motions(ours, theirs, profile_id);
    EXPECT_GT(o.compared, 0u);
    compared += o.compared;
  }
  // curves.stp alone has over 300 (its two-turn helix as straight points).
  EXPECT_GE(compared, 300u);
  // curves.stp's quarter and half circles must have come back as circles.
  EXPECT_GE(arcs, 2u);
}

TEST(RobotDialect, KukaKrlMotionsMatchTheCanonicalProgram) {
  check("kuka-krl", read_krl);
}
TEST(RobotDialect, AbbRapidMotionsMatchTheCanonicalProgram) {
  check("abb-rapid", read_rapid);
}

// The checkers can fail: one coordinate of one CIRC's auxiliary point (KRL) and of one MoveL's
// robtarget (RAPID), moved by 0.01 mm, is reported.
std::size_t failures_after(const std::string& profile_id, Reader read, const std::string& from,
                           const std::string& to) {
  const fs::path curves =
      test::source_dir() / "tests" / "golden" / "trace" / "cases" / "curves.stp";
  const Posted posted = post_file(curves, profile_id);
  if (!posted.profile) return 0;
  std::string text = posted.text;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return 0;
  text.replace(at, from.size(), to);
  const auto ours = robot_form(motions_of(posted.calls, options_for(posted.profile->profile)),
                               arc_planes(posted.calls));
  std::vector<std::string> errors;
  const auto theirs = read(text, errors);
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    (void)expect_same_motions(ours, theirs, profile_id);
  }
  return static_cast<std::size_t>(results.size());
}

TEST(RobotDialect, PerturbedCoordinateIsReported) {
  EXPECT_GT(failures_after("kuka-krl", read_krl, "CIRC {X 7.0711,", "CIRC {X 7.0811,"), 0u);
  EXPECT_GT(failures_after("abb-rapid", read_rapid, "MoveL [[10,0,0]", "MoveL [[10,0.01,0]"), 0u);
  // And the unperturbed text passes the same way (no false alarm from the replacement itself).
  EXPECT_EQ(failures_after("kuka-krl", read_krl, "CIRC {X 7.0711,", "CIRC {X 7.0711,"), 0u);
}

// Five-axis orientation: for tool axes off the vertical, the orientation written must turn the
// tool frame's Z onto -(i, j, k) (the tool points into the work, the STEP-NC axis away from
// it). KRL: Z column of Rz(A)·Ry(B)·Rx(C); RAPID: the quaternion applied to (0, 0, 1).
std::vector<canon::Call> tilted_program(const std::vector<canon::Direction>& axes) {
  std::vector<canon::Call> calls;
  calls.push_back(canon::Begin{canon::Scope::Project, {1, "PROJECT", "TILT"}});
  calls.push_back(canon::SetFeedRate{600});
  canon::Pose start{0, 0, 50, std::nullopt, canon::Direction{0, 0, 1}};
  calls.push_back(canon::StraightTraverse{start});
  double x = 0;
  for (const auto& axis : axes) {
    x += 10;
    calls.push_back(canon::StraightFeed{canon::Pose{x, 0, 0, std::nullopt, axis}});
  }
  calls.push_back(canon::ProgramEnd{});
  calls.push_back(canon::End{canon::Scope::Project, {1, "PROJECT", "TILT"}});
  return calls;
}

const std::vector<canon::Direction> kAxes{
    {0.5, 0, 0.8660254}, {0, -0.5, 0.8660254}, {0.3, 0.4, 0.8660254}, {-0.6, 0.3, 0.5}, {0, 0, 2}};

Vec minus_unit(const canon::Direction& d) {
  const double n = std::sqrt(d.i * d.i + d.j * d.j + d.k * d.k);
  return {-d.i / n, -d.j / n, -d.k / n};
}

std::string render(const std::string& profile_id, const std::vector<canon::Call>& calls) {
  xslt::initialise();
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  const auto profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(profile);
  if (!profile) return {};
  std::string text = render::render_program(*profile, calls, diagnostics);
  EXPECT_FALSE(diag::has_errors(diagnostics)) << diag::format(diagnostics.front());
  return text;
}

TEST(RobotDialect, KrlOrientationFollowsTheToolAxis) {
  const std::string text = render("kuka-krl", tilted_program(kAxes));
  static const std::regex abc(
      R"(LIN \{X [-0-9.]+, Y [-0-9.]+, Z [-0-9.]+, A ([-0-9.]+), B ([-0-9.]+), C ([-0-9.]+)\})");
  std::size_t n = 0;
  for (const auto& line : lines_of(text)) {
    std::smatch m;
    if (!std::regex_search(line, m, abc) || line.find("Z 0,") == std::string::npos) continue;
    ASSERT_LT(n, kAxes.size());
    const double deg = std::numbers::pi / 180;
    const double a = std::stod(m[1]) * deg, b = std::stod(m[2]) * deg, c = std::stod(m[3]) * deg;
    const Vec z{std::cos(a) * std::sin(b) * std::cos(c) + std::sin(a) * std::sin(c),
                std::sin(a) * std::sin(b) * std::cos(c) - std::cos(a) * std::sin(c),
                std::cos(b) * std::cos(c)};
    const Vec want = minus_unit(kAxes[n]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(z[k], want[k], 1e-4) << line;
    ++n;
  }
  EXPECT_EQ(n, kAxes.size()) << text;
}

TEST(RobotDialect, RapidQuaternionFollowsTheToolAxis) {
  const std::string text = render("abb-rapid", tilted_program(kAxes));
  static const std::regex quaternion(
      R"(MoveL \[\[[-0-9.]+,[-0-9.]+,0\],\[([-0-9.]+),([-0-9.]+),([-0-9.]+),([-0-9.]+)\])");
  std::size_t n = 0;
  for (const auto& line : lines_of(text)) {
    std::smatch m;
    if (!std::regex_search(line, m, quaternion)) continue;
    ASSERT_LT(n, kAxes.size());
    const double w = std::stod(m[1]), x = std::stod(m[2]), y = std::stod(m[3]), z = std::stod(m[4]);
    EXPECT_NEAR(w * w + x * x + y * y + z * z, 1, 1e-5) << line;
    const Vec tool_z{2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    const Vec want = minus_unit(kAxes[n]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(tool_z[k], want[k], 1e-5) << line;
    ++n;
  }
  EXPECT_EQ(n, kAxes.size()) << text;
}

// Chunk independence (docs/render.md): the robot stylesheets keep their state (first motion,
// velocity in force, arc start) in the job, so the text must not depend on where chunks are
// cut or how they are batched.
TEST(RobotDialect, ChunkedEqualsWholeProgram) {
  for (const char* id : {"kuka-krl", "abb-rapid"})
    for (const auto& input : cases()) {
      SCOPED_TRACE(std::string(id) + " " + input.filename().string());
      const Posted posted = post_file(input, id);
      ASSERT_TRUE(posted.profile);
      std::vector<diag::FileDiagnostic> d1, d2, d3;
      const std::string whole = render::render_program(*posted.profile, posted.calls, d1,
                                                       render::RenderOptions{{}, true});
      const std::string tiny = render::render_program(*posted.profile, posted.calls, d2,
                                                      render::RenderOptions{{3}, false, 0});
      const std::string batched = render::render_program(*posted.profile, posted.calls, d3,
                                                         render::RenderOptions{{3}, false, 600});
      EXPECT_FALSE(posted.text.empty());
      EXPECT_EQ(posted.text, whole);
      EXPECT_EQ(posted.text, tiny);
      EXPECT_EQ(posted.text, batched);
    }
}

}  // namespace
}  // namespace ncpost::interop
