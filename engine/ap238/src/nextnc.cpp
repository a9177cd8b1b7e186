// The Next-NC adapter: the Fusion 360 exporter of github.com/markmounteer/Fusion360Next-NC
// (the writer of the corpus's p21-aim/ files), as its docs/format.md and
// docs/native-profile-v2.md document its AP238 profile (next-nc/milling-toolpath/0.2):
//
// - 'next-nc circular motion' on a MACHINING_TOOLPATH: an arc or helix as a JSON object with
//   exactly start, end, center (points in the program's length unit), plane ("XY", "XZ" or
//   "YZ": normals +Z, +Y, +X), clockwise (about that normal), sweepRadians (the total angle,
//   positive, several turns allowed) and axialRise (the signed advance along the normal); the
//   centre is on the axis at the start's height. The toolpath has no basic curve beside it.
// - 'next-nc profile', 'next-nc required capabilities', 'next-nc coordinates' (workplan),
//   'next-nc tool offset', 'next-nc work offset', 'next-nc tolerance', 'next-nc entry point'
//   (operation), 'next-nc movement' (toolpath): what the job needs, the offsets the operator
//   selects, CAM's tolerance, the section's first point, the kind of move. None changes the
//   canonical program (motion kind comes from the standard speed profile); they are listed as
//   notes.
//
// The program's length unit is the unit of the operation's 'next-nc entry point' (a point in a
// geometric context with units, as the profile requires), else mm.

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "vendor.hpp"

namespace ncpost::ap238::detail {
namespace {

constexpr std::string_view kCircularMotion = "next-nc circular motion";
constexpr std::string_view kEntryPoint = "next-nc entry point";
constexpr std::string_view kDocumented[] = {
    "next-nc profile",     "next-nc required capabilities",
    "next-nc coordinates", "next-nc tool offset",
    "next-nc work offset", "next-nc tolerance",
    kEntryPoint,           "next-nc movement",
    kCircularMotion,
};
// The writer's own limits (docs/native-profile-v2.md): at most 10000 revolutions in one record,
// coordinates below 1e15. A longer text or deeper nesting than a flat object needs is refused
// before it is parsed.
constexpr double kMaxRevolutions = 10000;
constexpr double kMaxCoordinate = 1e15;
constexpr std::size_t kMaxJsonBytes = 4096;
constexpr int kMaxJsonDepth = 2;
constexpr double kTwoPi = 2 * std::numbers::pi;

// Bracket depth of a JSON text, strings skipped.
int json_depth(std::string_view text) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

std::optional<Vec3> json_point(const nlohmann::json& j) {
  if (!j.is_array() || j.size() != 3) return std::nullopt;
  double xyz[3];
  for (std::size_t i = 0; i < 3; ++i) {
    if (!j[i].is_number()) return std::nullopt;
    xyz[i] = j[i].get<double>();
    if (!std::isfinite(xyz[i]) || std::abs(xyz[i]) >= kMaxCoordinate) return std::nullopt;
  }
  return Vec3{xyz[0], xyz[1], xyz[2]};
}

// Angle of `p` about `axis` through `centre`, from `reference` (perpendicular to the axis).
double angle_about(Vec3 p, Vec3 centre, Vec3 axis, Vec3 reference) {
  const Vec3 d = p - centre;
  const Vec3 in_plane = d - axis * d.dot(axis);
  return std::atan2(in_plane.dot(axis.cross(reference)), in_plane.dot(reference));
}

class NextNc final : public VendorAdapter {
 public:
  [[nodiscard]] std::string_view vendor() const override { return "Next-NC"; }
  [[nodiscard]] bool documents(std::string_view property) const override {
    for (const std::string_view name : kDocumented)
      if (name == property) return true;
    return false;
  }
  [[nodiscard]] bool is_geometry(std::string_view property) const override {
    return property == kCircularMotion;
  }

  [[nodiscard]] std::optional<std::vector<Segment>> toolpath_geometry(
      Aim& aim, const Instance& operation, const Instance& toolpath, const Property& property,
      double arc_tolerance) const override {
    const auto fail = [&](const std::string& why) {
      aim.report(diag::Code::Ap238VendorGeometry, toolpath,
                 aim.describe(toolpath) + " '" + aim.text(toolpath, "name") + "': its '" +
                     std::string(kCircularMotion) + "' " + why);
      return std::nullopt;
    };
    const auto text = aim.description_of(aim.item(property, "descriptive_representation_item"));
    if (!text) return fail("has no descriptive item");
    if (text->size() > kMaxJsonBytes || json_depth(*text) > kMaxJsonDepth)
      return fail("is not a flat JSON object of at most " + std::to_string(kMaxJsonBytes) +
                  " bytes");
    const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return fail("is not a JSON object");
    static constexpr std::string_view kKeys[] = {"start",     "end",          "center",   "plane",
                                                 "clockwise", "sweepRadians", "axialRise"};
    if (j.size() != std::size(kKeys))
      return fail("does not have exactly the seven documented keys");
    for (const std::string_view key : kKeys)
      if (!j.contains(key)) return fail("lacks '" + std::string(key) + "'");
    const auto start = json_point(j["start"]);
    const auto end = json_point(j["end"]);
    const auto centre = json_point(j["center"]);
    if (!start || !end || !centre) return fail("has a point that is not three finite numbers");
    const std::string plane = j["plane"].is_string() ? j["plane"].get<std::string>() : "";
    const Vec3 normal = plane == "XY"   ? Vec3{0, 0, 1}
                        : plane == "XZ" ? Vec3{0, 1, 0}
                        : plane == "YZ" ? Vec3{1, 0, 0}
                                        : Vec3{};
    if (normal.length() == 0) return fail("names no plane of XY, XZ, YZ");
    if (!j["clockwise"].is_boolean() || !j["sweepRadians"].is_number() ||
        !j["axialRise"].is_number())
      return fail("has a clockwise that is not a boolean or a sweep or rise that is no number");
    const bool clockwise = j["clockwise"].get<bool>();
    const double sweep = j["sweepRadians"].get<double>();
    const double rise = j["axialRise"].get<double>();
    if (!std::isfinite(sweep) || sweep <= 0 || sweep > kMaxRevolutions * kTwoPi ||
        !std::isfinite(rise) || std::abs(rise) >= kMaxCoordinate)
      return fail("has a sweep outside (0, " + std::to_string(int(kMaxRevolutions)) +
                  " turns] or a rise that is not finite");

    const double mm = length_unit(aim, operation);
    const double tolerance = arc_tolerance / mm;  // in the program's unit
    // Right-handed bases: XY = (X, Y), XZ = (Z, X), YZ = (Y, Z).
    const Vec3 reference = plane == "XY"   ? Vec3{1, 0, 0}
                           : plane == "XZ" ? Vec3{0, 0, 1}
                                           : Vec3{0, 1, 0};
    const double r0 = ((*start - *centre) - normal * (*start - *centre).dot(normal)).length();
    const double r1 = ((*end - *centre) - normal * (*end - *centre).dot(normal)).length();
    if (std::abs(r0 - r1) > tolerance || r0 <= tolerance)
      return fail("has start and end " + std::to_string(r0) + " and " + std::to_string(r1) +
                  " from its axis");
    if (std::abs((*start - *centre).dot(normal)) > tolerance)
      return fail("has its centre off the start's height");
    if (std::abs((*end - *start).dot(normal) - rise) > tolerance)
      return fail("has an axial rise of " + std::to_string(rise) + " but its end is " +
                  std::to_string((*end - *start).dot(normal)) + " above its start");
    // The sweep must end at the end point's angle (modulo whole turns).
    const double a0 = angle_about(*start, *centre, normal, reference);
    const double a1 = angle_about(*end, *centre, normal, reference);
    const double travelled = std::fmod((clockwise ? a0 - a1 : a1 - a0) + 2 * kTwoPi, kTwoPi);
    double off = std::abs(std::fmod(sweep, kTwoPi) - travelled);
    off = std::min(off, kTwoPi - off);
    if (off * r0 > tolerance)
      return fail("sweeps " + std::to_string(sweep) + " rad, which does not end at its end point");
    // rs274's count: |turns| - 1 full turns, then the rest (a full turn when the rest is 0).
    const double full = std::floor(sweep / kTwoPi + 1e-9);
    const bool whole = std::abs(sweep - full * kTwoPi) * r0 <= tolerance;
    const int turns = static_cast<int>(whole ? std::max(full, 1.0) : full + 1);
    Segment s;
    s.kind = Segment::Kind::Arc;
    s.start = *start * mm;
    s.end = *end * mm;
    s.centre = *centre * mm;
    s.normal = normal;
    s.turns = clockwise ? -turns : turns;
    return std::vector<Segment>{s};
  }

 private:
  static double length_unit(Aim& aim, const Instance& operation) {
    for (const Property& p : aim.properties(operation))
      if (p.name == kEntryPoint && !p.representations.empty())
        return aim.context_units(*p.representations.front()).mm_per_length;
    return 1;
  }
};

const NextNc kNextNc;
const VendorAdapter* const kAdapters[] = {&kNextNc};

}  // namespace

std::span<const VendorAdapter* const> vendor_adapters() {
  return kAdapters;
}

}  // namespace ncpost::ap238::detail
