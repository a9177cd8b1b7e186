// profile.json → Profile, validated by hand against the rules of stylesheets/profile.schema.json
// (Debian has no JSON Schema library for C++). tests/unit/profile checks that both agree.

#include "ncpost/profile/profile.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "ncpost/diag/json.hpp"

namespace ncpost::profile {
namespace {

using nlohmann::json;

class Checker {
 public:
  explicit Checker(std::vector<diag::Diagnostic>& out) : out_(out) {}

  void fail(const std::string& path, const std::string& message,
            diag::Code code = diag::Code::ProfileInvalid) {
    ok_ = false;
    out_.push_back(diag::make(code, 0, 0, path + ": " + message));
  }
  [[nodiscard]] bool ok() const noexcept { return ok_; }

  // An object with exactly these keys allowed, `required` among them.
  const json* object(const json& parent, const std::string& path, std::string_view key,
                     bool required, std::initializer_list<std::string_view> allowed,
                     std::initializer_list<std::string_view> must) {
    const json* node = member(parent, path, key, required);
    if (!node) return nullptr;
    const std::string here = path + "/" + std::string(key);
    if (!node->is_object()) {
      fail(here, "must be an object");
      return nullptr;
    }
    check_keys(*node, here, allowed, must);
    return node;
  }

  void check_keys(const json& node, const std::string& here,
                  std::initializer_list<std::string_view> allowed,
                  std::initializer_list<std::string_view> must) {
    for (const auto& [k, v] : node.items()) {
      bool known = false;
      for (auto a : allowed) known = known || a == k;
      if (!known) fail(here + "/" + k, "unknown field");
    }
    for (auto m : must)
      if (!node.contains(std::string(m))) fail(here + "/" + std::string(m), "missing (required)");
  }

  const json* member(const json& parent, const std::string& /*path*/, std::string_view key,
                     bool /*required*/) {
    auto it = parent.find(std::string(key));
    if (it == parent.end()) return nullptr;  // a missing required field is reported by check_keys
    return &*it;
  }

  std::optional<std::string> string(const json& parent, const std::string& path,
                                    std::string_view key, std::size_t min_length = 0,
                                    std::size_t max_length = 200) {
    const json* node = member(parent, path, key, false);
    if (!node) return std::nullopt;
    const std::string here = path + "/" + std::string(key);
    if (!node->is_string()) {
      fail(here, "must be a string");
      return std::nullopt;
    }
    auto s = node->get<std::string>();
    if (s.size() < min_length || s.size() > max_length) {
      fail(here,
           "length must be " + std::to_string(min_length) + ".." + std::to_string(max_length));
      return std::nullopt;
    }
    return s;
  }

  std::optional<std::string> enumeration(const json& parent, const std::string& path,
                                         std::string_view key,
                                         std::initializer_list<std::string_view> values) {
    auto s = string(parent, path, key);
    if (!s) return std::nullopt;
    for (auto v : values)
      if (v == *s) return s;
    std::string list;
    for (auto v : values) list += (list.empty() ? "" : ", ") + std::string(v);
    fail(path + "/" + std::string(key), "must be one of " + list);
    return std::nullopt;
  }

  std::optional<bool> boolean(const json& parent, const std::string& path, std::string_view key) {
    const json* node = member(parent, path, key, false);
    if (!node) return std::nullopt;
    if (!node->is_boolean()) {
      fail(path + "/" + std::string(key), "must be true or false");
      return std::nullopt;
    }
    return node->get<bool>();
  }

  std::optional<double> number(const json& parent, const std::string& path, std::string_view key,
                               double min = -1e300, double max = 1e300,
                               bool exclusive_min = false) {
    const json* node = member(parent, path, key, false);
    if (!node) return std::nullopt;
    const std::string here = path + "/" + std::string(key);
    if (!node->is_number()) {
      fail(here, "must be a number");
      return std::nullopt;
    }
    const double v = node->get<double>();
    if (!std::isfinite(v) || v < min || v > max || (exclusive_min && v <= min)) {
      fail(here, "out of range");
      return std::nullopt;
    }
    return v;
  }

  std::optional<std::int64_t> integer(const json& parent, const std::string& path,
                                      std::string_view key, std::int64_t min, std::int64_t max) {
    const json* node = member(parent, path, key, false);
    if (!node) return std::nullopt;
    const std::string here = path + "/" + std::string(key);
    if (!node->is_number_integer()) {
      fail(here, "must be an integer");
      return std::nullopt;
    }
    const auto v = node->get<std::int64_t>();
    if (v < min || v > max) {
      fail(here, "must be " + std::to_string(min) + ".." + std::to_string(max));
      return std::nullopt;
    }
    return v;
  }

  std::optional<std::array<double, 3>> vector3(const json& parent, const std::string& path,
                                               std::string_view key) {
    const json* node = member(parent, path, key, false);
    if (!node) return std::nullopt;
    const std::string here = path + "/" + std::string(key);
    if (!node->is_array() || node->size() != 3) {
      fail(here, "must be an array of 3 numbers");
      return std::nullopt;
    }
    std::array<double, 3> v{};
    for (std::size_t i = 0; i < 3; ++i) {
      if (!(*node)[i].is_number()) {
        fail(here, "must be an array of 3 numbers");
        return std::nullopt;
      }
      v[i] = (*node)[i].get<double>();
    }
    return v;
  }

 private:
  std::vector<diag::Diagnostic>& out_;
  bool ok_ = true;
};

void read_format(Checker& c, const json& formats, std::string_view quantity,
                 xslt::NumberFormat& f) {
  const json* q = c.object(formats, "/formats", quantity, true,
                           {"decimals", "decimal_point", "leading_zero", "trailing_zeros", "scale"},
                           {"decimals", "decimal_point", "leading_zero", "trailing_zeros"});
  if (!q) return;
  const std::string path = "/formats/" + std::string(quantity);
  if (auto v = c.integer(*q, path, "decimals", 0, 12)) f.decimals = static_cast<int>(*v);
  if (auto v = c.boolean(*q, path, "decimal_point")) f.decimal_point = *v;
  if (auto v = c.boolean(*q, path, "leading_zero")) f.leading_zero = *v;
  if (auto v = c.boolean(*q, path, "trailing_zeros")) f.trailing_zeros = *v;
  if (auto v = c.number(*q, path, "scale", 0, 1e9, true)) f.scale = *v;
}

std::optional<Range> read_range(Checker& c, const json& travel, std::string_view axis) {
  const json* r = c.object(travel, "/limits/travel", axis, false, {"min", "max"}, {"min", "max"});
  if (!r) return std::nullopt;
  const std::string path = "/limits/travel/" + std::string(axis);
  auto lo = c.number(*r, path, "min");
  auto hi = c.number(*r, path, "max");
  if (!lo || !hi) return std::nullopt;
  if (*lo > *hi) {
    c.fail(path, "min is greater than max");
    return std::nullopt;
  }
  return Range{*lo, *hi};
}

// output.mime_type and output.extension go into response headers (Content-Type, and the file
// name of Content-Disposition) as they are, so they are held to what those headers may carry:
// a media type of RFC 6838 names with plain parameters, and a file-name suffix of letters,
// digits, '.', '_' and '-'. A CR or LF would otherwise start a header of the profile's own.
// The same patterns are in profile.schema.json.
bool valid_media_type(const std::string& text) {
  static const std::regex media_type(
      "^[A-Za-z0-9][A-Za-z0-9!#$&^_.+-]*/[A-Za-z0-9][A-Za-z0-9!#$&^_.+-]*"
      "( *; *[A-Za-z0-9!#$&^_.+-]+=[A-Za-z0-9!#$&^_.+-]+)*$");
  return std::regex_match(text, media_type);
}

bool valid_extension(std::string_view text) {
  for (const char ch : text) {
    const bool alnum =
        (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
    if (!alnum && ch != '.' && ch != '_' && ch != '-') return false;
  }
  return true;
}

// ---- kinematics (docs/kinematics.md) ----

constexpr double kMaxAxisDegrees = 36000;  // a hundred turns either way

std::optional<RotaryAxis> read_rotary_axis(Checker& c, const json& kin, std::string_view role) {
  const json* a = c.object(kin, "/kinematics", role, true,
                           {"name", "axis", "direction", "continuous", "min", "max", "pivot"},
                           {"name", "axis", "direction"});
  if (!a) return std::nullopt;
  const std::string path = "/kinematics/" + std::string(role);
  RotaryAxis axis;
  bool good = true;
  if (auto v = c.enumeration(*a, path, "name", {"A", "B", "C"}))
    axis.name = (*v)[0];
  else
    good = false;
  if (auto v = c.enumeration(*a, path, "axis", {"x", "y", "z"}))
    axis.axis = *v == "x" ? MachineAxis::X : *v == "y" ? MachineAxis::Y : MachineAxis::Z;
  else
    good = false;
  const auto direction = c.integer(*a, path, "direction", -1, 1);
  if (direction && *direction != 0) {
    axis.direction = static_cast<int>(*direction);
  } else {
    if (direction) c.fail(path + "/direction", "must be 1 or -1");
    good = false;
  }
  if (auto v = c.boolean(*a, path, "continuous")) axis.continuous = *v;
  const auto lo = c.number(*a, path, "min", -kMaxAxisDegrees, kMaxAxisDegrees);
  const auto hi = c.number(*a, path, "max", -kMaxAxisDegrees, kMaxAxisDegrees);
  if (axis.continuous) {
    if (a->contains("min") || a->contains("max")) {
      c.fail(path, "a continuous axis has no min and max");
      good = false;
    }
  } else if (!a->contains("min") || !a->contains("max")) {
    c.fail(path, "min and max are required unless the axis is continuous");
    good = false;
  } else if (lo && hi) {
    if (*lo >= *hi) {
      c.fail(path, "min must be less than max");
      good = false;
    }
    axis.min = *lo;
    axis.max = *hi;
  }
  if (auto v = c.vector3(*a, path, "pivot")) axis.pivot = *v;
  if (!good) return std::nullopt;
  return axis;
}

std::optional<Kinematics> read_kinematics(Checker& c, const json& doc) {
  const json* k = c.object(doc, "", "kinematics", false,
                           {"type", "primary", "secondary", "solution", "tool_centre_point",
                            "pole_tolerance", "rotation_warning"},
                           {"type", "primary", "secondary"});
  if (!k) return std::nullopt;
  Kinematics kin;
  const auto type =
      c.enumeration(*k, "/kinematics", "type", {"head-head", "table-table", "head-table"});
  if (type)
    kin.type = *type == "head-head"     ? KinematicsType::HeadHead
               : *type == "table-table" ? KinematicsType::TableTable
                                        : KinematicsType::HeadTable;
  const auto primary = read_rotary_axis(c, *k, "primary");
  const auto secondary = read_rotary_axis(c, *k, "secondary");
  if (auto v = c.enumeration(*k, "/kinematics", "solution",
                             {"shortest", "positive_tilt", "negative_tilt"}))
    kin.solution = *v == "shortest"        ? RotarySolution::Shortest
                   : *v == "positive_tilt" ? RotarySolution::PositiveTilt
                                           : RotarySolution::NegativeTilt;
  if (auto v = c.boolean(*k, "/kinematics", "tool_centre_point")) kin.tool_centre_point = *v;
  if (auto v = c.number(*k, "/kinematics", "pole_tolerance", 0, 1e-3, true))
    kin.pole_tolerance = *v;
  if (auto v = c.number(*k, "/kinematics", "rotation_warning", 0, 360)) kin.rotation_warning = *v;
  if (!type || !primary || !secondary) return std::nullopt;
  kin.primary = *primary;
  kin.secondary = *secondary;
  // The solver needs a tilting axis across the tool (X or Y) and a second axis across that:
  // docs/kinematics.md, "The machine".
  const RotaryAxis& tilt = kin.type == KinematicsType::HeadHead ? kin.secondary : kin.primary;
  if (kin.primary.name == kin.secondary.name)
    c.fail("/kinematics/secondary/name", "must differ from the primary axis's name");
  if (kin.primary.axis == kin.secondary.axis)
    c.fail("/kinematics/secondary/axis", "must differ from the primary axis's machine axis");
  if (tilt.axis == MachineAxis::Z)
    c.fail(std::string("/kinematics/") +
               (kin.type == KinematicsType::HeadHead ? "secondary" : "primary") + "/axis",
           "the tilting axis must turn about x or y");
  return kin;
}

// capabilities.output_options: the output options the stylesheet honours, each once.
void read_output_options(Checker& c, const json& cap, Profile& p) {
  const auto it = cap.find("output_options");
  if (it == cap.end()) return;
  if (!it->is_array()) {
    c.fail("/capabilities/output_options", "must be an array of output option names");
    return;
  }
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string here = "/capabilities/output_options/" + std::to_string(i);
    canon::OutputOption option{};
    const json& v = (*it)[i];
    if (!v.is_string() || !canon::find_output_option(v.get<std::string>(), option)) {
      c.fail(here, "must be block_numbers or subprogram");
    } else if (p.honours(option)) {
      c.fail(here, "is named twice");
    } else {
      p.output_options.push_back(option);
    }
  }
}

// The output options of checks.operation_rules[].options must be ones the renderer knows
// (canon/output_options.hpp), with the values it knows: PROFILE-010 when a profile is loaded
// or uploaded, not only when a CL program is posted. The rest of the section is cls's to check
// (CLS-100 at post time).
void check_rule_options(Checker& c, const json& checks) {
  const auto rules = checks.find("operation_rules");
  if (rules == checks.end() || !rules->is_array()) return;
  for (std::size_t i = 0; i < rules->size(); ++i) {
    const json& rule = (*rules)[i];
    if (!rule.is_object()) continue;
    const auto options = rule.find("options");
    if (options == rule.end() || !options->is_object()) continue;
    const std::string match =
        rule.contains("match") && rule["match"].is_string() ? rule["match"].get<std::string>() : "";
    for (const auto& [name, value] : options->items()) {
      canon::OutputOptions scratch;
      const std::string problem =
          value.is_string() ? canon::set_output_option(scratch, name, value.get<std::string>())
                            : "output option '" + name + "' must be the string 'on' or 'off'";
      if (!problem.empty())
        c.fail("/checks/operation_rules/" + std::to_string(i) + "/options/" + name,
               "the rule matching '" + match + "' selects an " + problem,
               diag::Code::ProfileOutputOption);
    }
  }
}

}  // namespace

bool valid_id(std::string_view id) noexcept {
  if (id.empty() || id.size() > 64) return false;
  for (std::size_t i = 0; i < id.size(); ++i) {
    const char ch = id[i];
    const bool alnum = (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9');
    if (!alnum && (i == 0 || (ch != '.' && ch != '_' && ch != '-'))) return false;
  }
  return true;
}

std::optional<Profile> parse_profile(std::string_view text,
                                     std::vector<diag::Diagnostic>& diagnostics) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    diagnostics.push_back(diag::json_syntax_error(diag::Code::ProfileJson, text, e));
    return std::nullopt;
  }
  Checker c(diagnostics);
  if (!doc.is_object()) {
    c.fail("", "must be an object");
    return std::nullopt;
  }
  Profile p;
  c.check_keys(
      doc, "",
      {"$schema", "id", "name", "controller", "mode", "output", "block_numbers", "formats", "units",
       "capabilities", "setup", "limits", "render", "checks", "kinematics"},
      {"id", "name", "controller", "output", "block_numbers", "formats", "units", "capabilities"});
  if (auto v = c.string(doc, "", "id", 1, 64)) {
    if (valid_id(*v))
      p.id = *v;
    else
      c.fail("/id", "must match ^[a-z0-9][a-z0-9._-]*$");
  }
  if (auto v = c.string(doc, "", "name", 1, 200)) p.name = *v;
  if (auto v = c.string(doc, "", "controller", 1, 64)) p.controller = *v;
  if (auto v = c.enumeration(doc, "", "mode", {"canonical", "raw"}))
    p.mode = *v == "raw" ? Mode::Raw : Mode::Canonical;

  if (const json* o =
          c.object(doc, "", "output", true,
                   {"extension", "mime_type", "line_ending", "program_number", "error_marker"},
                   {"extension", "mime_type", "line_ending"})) {
    if (auto v = c.string(*o, "/output", "extension", 0, 16)) {
      if (valid_extension(*v))
        p.extension = *v;
      else
        c.fail("/output/extension", "must match ^[A-Za-z0-9._-]*$");
    }
    if (auto v = c.string(*o, "/output", "mime_type", 1, 100)) {
      if (valid_media_type(*v))
        p.mime_type = *v;
      else
        c.fail("/output/mime_type", "must be a media type such as text/plain; charset=utf-8");
    }
    if (auto v = c.enumeration(*o, "/output", "line_ending", {"lf", "crlf"}))
      p.line_ending = *v == "lf" ? "\n" : "\r\n";
    if (o->contains("error_marker")) {
      if (auto v = c.string(*o, "/output", "error_marker", 9, 200)) {
        if (v->find("{message}") == std::string::npos)
          c.fail("/output/error_marker", "must contain {message}");
        p.error_marker = *v;
      }
    }
    if (const json* pn = c.object(*o, "/output", "program_number", false, {"value", "min", "max"},
                                  {"value", "min", "max"})) {
      auto value = c.integer(*pn, "/output/program_number", "value", 0, 99999999);
      auto lo = c.integer(*pn, "/output/program_number", "min", 0, 99999999);
      auto hi = c.integer(*pn, "/output/program_number", "max", 0, 99999999);
      if (value && lo && hi) {
        if (*value < *lo || *value > *hi)
          c.fail("/output/program_number/value", "outside min..max");
        p.program_number = *value;
        p.program_number_min = *lo;
        p.program_number_max = *hi;
      }
    }
  }
  if (const json* b = c.object(doc, "", "block_numbers", true,
                               {"start", "increment", "maximum", "wrap", "numbered"},
                               {"start", "increment", "maximum", "wrap"})) {
    if (auto v = c.integer(*b, "/block_numbers", "start", 0, 99999999)) p.block.start = *v;
    if (auto v = c.integer(*b, "/block_numbers", "increment", 1, 99999999)) p.block.increment = *v;
    if (auto v = c.integer(*b, "/block_numbers", "maximum", 1, 99999999)) p.block.maximum = *v;
    if (auto v = c.boolean(*b, "/block_numbers", "wrap")) p.block_wrap = *v;
    if (b->contains("numbered")) {
      if (auto v = c.boolean(*b, "/block_numbers", "numbered")) p.block.numbered = *v;
    }
    if (p.block.start > p.block.maximum) c.fail("/block_numbers/start", "greater than maximum");
  }
  if (const json* f =
          c.object(doc, "", "formats", true, {"length", "angle", "feed", "speed", "dwell"},
                   {"length", "angle", "feed", "speed", "dwell"})) {
    read_format(c, *f, "length", p.length);
    read_format(c, *f, "angle", p.angle);
    read_format(c, *f, "feed", p.feed);
    read_format(c, *f, "speed", p.speed);
    read_format(c, *f, "dwell", p.dwell);
  }
  if (auto v = c.enumeration(doc, "", "units", {"mm", "inch"}))
    p.units = *v == "mm" ? xslt::Units::Millimetre : xslt::Units::Inch;
  if (const json* cap = c.object(
          doc, "", "capabilities", true,
          {"arcs", "helical", "canned_cycles", "nurbs", "chord_tolerance", "output_options"},
          {"arcs", "helical", "canned_cycles", "nurbs"})) {
    if (auto v = c.enumeration(*cap, "/capabilities", "arcs", {"ijk", "r", "none"}))
      p.arcs = *v == "ijk" ? Arcs::Ijk : *v == "r" ? Arcs::R : Arcs::None;
    if (auto v = c.boolean(*cap, "/capabilities", "helical")) p.helical = *v;
    if (auto v = c.enumeration(*cap, "/capabilities", "canned_cycles", {"native", "expand"}))
      p.canned_cycles = *v == "native" ? CannedCycles::Native : CannedCycles::Expand;
    if (auto v = c.enumeration(*cap, "/capabilities", "nurbs", {"native", "linearize"}))
      p.nurbs = *v == "native" ? NurbsMode::Native : NurbsMode::Linearize;
    if (auto v = c.number(*cap, "/capabilities", "chord_tolerance", 0, 10, true))
      p.chord_tolerance = *v;
    read_output_options(c, *cap, p);
  }
  if (const json* s =
          c.object(doc, "", "setup", false, {"axis", "angle", "translation", "matrix"}, {})) {
    if (s->contains("matrix")) {
      const json& m = (*s)["matrix"];
      bool good = m.is_array() && m.size() == 9;
      for (std::size_t i = 0; good && i < 9; ++i) good = m[i].is_number();
      if (!good)
        c.fail("/setup/matrix", "must be an array of 9 numbers (row-major)");
      else
        for (std::size_t i = 0; i < 9; ++i) p.setup.matrix[i] = m[i].get<double>();
      if (s->contains("axis") || s->contains("angle"))
        c.fail("/setup", "give either matrix or axis and angle");
      if (auto t = c.vector3(*s, "/setup", "translation")) p.setup.translation = *t;
    } else {
      auto axis = c.vector3(*s, "/setup", "axis").value_or(std::array<double, 3>{0, 0, 1});
      auto angle = c.number(*s, "/setup", "angle", -360, 360).value_or(0);
      auto t = c.vector3(*s, "/setup", "translation").value_or(std::array<double, 3>{0, 0, 0});
      if (std::hypot(axis[0], axis[1], axis[2]) == 0)
        c.fail("/setup/axis", "must not be the zero vector");
      else
        p.setup = xslt::SetupTransform::from_rotation(axis, angle, t);
    }
  }
  if (const json* r = c.object(doc, "", "render", false, {"motion_runs"}, {})) {
    if (r->contains("motion_runs")) {
      const json& kinds = (*r)["motion_runs"];
      if (!kinds.is_array()) c.fail("/render/motion_runs", "must be an array of call names");
      for (std::size_t i = 0; kinds.is_array() && i < kinds.size(); ++i) {
        const std::string here = "/render/motion_runs/" + std::to_string(i);
        const std::string kind = kinds[i].is_string() ? kinds[i].get<std::string>() : "";
        bool* flag = kind == "STRAIGHT_TRAVERSE" ? &p.motion_runs.traverse
                     : kind == "STRAIGHT_FEED"   ? &p.motion_runs.feed
                     : kind == "ARC_FEED"        ? &p.motion_runs.arc
                                                 : nullptr;
        if (flag == nullptr)
          c.fail(here, "must be STRAIGHT_TRAVERSE, STRAIGHT_FEED or ARC_FEED");
        else if (*flag)
          c.fail(here, "is named twice");
        else
          *flag = true;
      }
    }
  }
  if (const json* l = c.object(
          doc, "", "limits", false,
          {"travel", "max_feed", "max_spindle", "tool_number", "max_line_length", "severity"},
          {})) {
    if (const json* t = c.object(*l, "/limits", "travel", false, {"x", "y", "z"}, {})) {
      p.limits.x = read_range(c, *t, "x");
      p.limits.y = read_range(c, *t, "y");
      p.limits.z = read_range(c, *t, "z");
    }
    p.limits.max_feed = c.number(*l, "/limits", "max_feed", 0, 1e9, true);
    p.limits.max_spindle = c.number(*l, "/limits", "max_spindle", 0, 1e9, true);
    if (const json* t =
            c.object(*l, "/limits", "tool_number", false, {"min", "max"}, {"min", "max"})) {
      auto lo = c.integer(*t, "/limits/tool_number", "min", 0, 99999999);
      auto hi = c.integer(*t, "/limits/tool_number", "max", 0, 99999999);
      if (lo && hi) {
        if (*lo > *hi) c.fail("/limits/tool_number", "min is greater than max");
        p.limits.tool_number = std::array<std::int64_t, 2>{*lo, *hi};
      }
    }
    if (auto v = c.integer(*l, "/limits", "max_line_length", 0, 100000))
      p.limits.max_line_length = static_cast<std::size_t>(*v);
    if (auto v = c.enumeration(*l, "/limits", "severity", {"warning", "error"}))
      p.limits.severity = *v == "error" ? diag::Severity::Error : diag::Severity::Warning;
  }
  // Carried as text: engine/cls reads and checks it (cls::parse_checks), so that the profile stage
  // does not depend on the CL reader.
  if (const auto it = doc.find("checks"); it != doc.end()) {
    if (it->is_object()) {
      p.checks_json = it->dump();
      check_rule_options(c, *it);
    } else {
      c.fail("/checks", "must be an object");
    }
  }
  p.kinematics = read_kinematics(c, doc);
  // The kinematics turn tool axes given in program axes, while a set-up rotation turns only
  // the points the stylesheet writes (ext:setup-x/y/z): together they would disagree, so a
  // five-axis profile's set-up may only translate (docs/kinematics.md).
  if (p.kinematics && p.setup.matrix != xslt::SetupTransform{}.matrix)
    c.fail("/setup", "with kinematics the set-up may only translate (angle 0, identity matrix)");
  if (!c.ok()) return std::nullopt;
  return p;
}

xslt::JobConfig job_config(const Profile& p) {
  xslt::JobConfig config;
  config.units = p.units;
  config.length = p.length;
  config.angle = p.angle;
  config.feed = p.feed;
  config.speed = p.speed;
  config.dwell = p.dwell;
  config.block = p.block;
  // No wrap: the counter runs on past `maximum` (the xslt API always wraps at maximum).
  if (!p.block_wrap) config.block.maximum = std::numeric_limits<std::int64_t>::max() / 2;
  config.setup = p.setup;
  config.max_line_length = p.limits.max_line_length;
  if (p.kinematics) {
    config.rotary_axes = {false, false, false};
    for (const char name : {p.kinematics->primary.name, p.kinematics->secondary.name})
      config.rotary_axes[static_cast<std::size_t>(name - 'A')] = true;
  }
  return config;
}

}  // namespace ncpost::profile
