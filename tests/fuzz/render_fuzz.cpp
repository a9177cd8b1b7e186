// libFuzzer target for the render stage (engine/render): fuzzed canonical programs rendered
// under one fixed built-in profile (linuxcnc; a program with a tool axis also under
// linuxcnc-5ax, whose kinematics turn tool axes into rotary positions). The bytes are read as
// canonical trace text, the form `ncpost trace` writes (docs/canon.md), by a lenient decoder
// here: one call per line, `NAME(arguments)` after an optional line number, missing arguments
// 0, any number strtod reads (nan, inf, 1e308, hex). The tests/golden/trace cases are the seeds.
// Rendering must never crash, hang or trip a sanitizer; the stylesheet's limits bound it, and
// a render reports a failure only with an error diagnostic.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace canon = ncpost::canon;

namespace {

// ---- the decoder ---------------------------------------------------------------------------

// The arguments of one call, split at the commas outside quotes, brackets and parentheses.
std::vector<std::string_view> split_arguments(std::string_view s) {
  std::vector<std::string_view> out;
  int depth = 0;
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quoted) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '(' || c == '[') {
      ++depth;
    } else if (c == ')' || c == ']') {
      --depth;
    } else if (c == ',' && depth == 0) {
      out.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  }
  if (start < s.size() || !out.empty()) out.push_back(s.substr(start));
  for (auto& a : out) {
    while (!a.empty() && a.front() == ' ') a.remove_prefix(1);
    while (!a.empty() && a.back() == ' ') a.remove_suffix(1);
  }
  return out;
}

double number(std::string_view s) {
  const std::string copy(s.substr(0, 400));
  return std::strtod(copy.c_str(), nullptr);
}

std::string unquote(std::string_view s) {
  if (s.size() < 2 || s.front() != '"') return std::string(s);
  s = s.substr(1, s.size() - 2);
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\' || i + 1 == s.size()) {
      out += s[i];
      continue;
    }
    const char e = s[++i];
    if (e == 'n')
      out += '\n';
    else if (e == 'r')
      out += '\r';
    else if (e == 't')
      out += '\t';
    else if (e == 'x' && i + 2 < s.size()) {
      out += static_cast<char>(std::strtol(std::string(s.substr(i + 1, 2)).c_str(), nullptr, 16));
      i += 2;
    } else
      out += e;
  }
  return out;
}

struct Arguments {
  std::vector<std::string_view> items;
  std::size_t at = 0;
  [[nodiscard]] std::size_t left() const { return items.size() - std::min(at, items.size()); }
  double next() { return at < items.size() ? number(items[at++]) : 0.0; }
  // A count or a sign (turns, rotation, degree) as the readers give them: whole and small. A
  // value past int's range (1e308) is clamped, not converted (undefined behaviour).
  int whole() {
    const double v = next();
    return std::isfinite(v) ? static_cast<int>(std::clamp(v, -1e6, 1e6)) : 0;
  }
  std::string_view word() { return at < items.size() ? items[at++] : std::string_view{}; }
  // Three more numbers after `fixed`: a rotary position or a tool axis; six: both. Three are a
  // tool axis when of unit length, as the readers write them, else rotary positions.
  void tail(std::optional<canon::Rotary>& rotary, std::optional<canon::Direction>& axis) {
    if (left() >= 6) {
      rotary = canon::Rotary{next(), next(), next()};
      axis = canon::Direction{next(), next(), next()};
    } else if (left() >= 3) {
      const double a = next(), b = next(), c = next();
      const double length = a * a + b * b + c * c;
      if (length > 0.999 && length < 1.001)
        axis = canon::Direction{a, b, c};
      else
        rotary = canon::Rotary{a, b, c};
    }
  }
  canon::Pose pose() {
    canon::Pose p{next(), next(), next()};
    tail(p.rotary, p.tool_axis);
    return p;
  }
};

// Every call by its trace name, default-constructed: the calls without arguments need nothing
// more, the others are filled in below.
const std::map<std::string, canon::Call, std::less<>>& calls_by_name() {
  static const auto table = [] {
    std::map<std::string, canon::Call, std::less<>> t;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (t.emplace(std::string(canon::name(canon::Call{std::in_place_index<I>})),
                 canon::Call{std::in_place_index<I>}),
       ...);
    }
    (std::make_index_sequence<std::variant_size_v<canon::Call>>{});
    for (const auto scope : {canon::Scope::Project, canon::Scope::Setup, canon::Scope::Workplan,
                             canon::Scope::Workingstep}) {
      t.emplace(std::string(canon::marker_name(scope, true)), canon::Begin{scope});
      t.emplace(std::string(canon::marker_name(scope, false)), canon::End{scope});
    }
    for (const auto kind : {canon::CycleKind::Drill, canon::CycleKind::PeckDrill,
                            canon::CycleKind::Tap, canon::CycleKind::Bore, canon::CycleKind::Ream})
      t.emplace(std::string(canon::name(kind)), canon::Cycle{kind});
    t.emplace("ARC_FEED_3D", canon::ArcFeed{});
    return t;
  }();
  return table;
}

canon::Entity entity(Arguments& a) {
  canon::Entity e;
  const auto id = a.word();
  if (id.starts_with('#')) e.id = std::strtoull(std::string(id.substr(1, 20)).c_str(), nullptr, 10);
  const auto type = a.word();
  if (type != "$") e.type = unquote(type);
  e.name = unquote(a.word());
  return e;
}

struct Decoder {
  canon::Plane plane = canon::Plane::Xy;

  void fill(canon::Call& call, std::string_view name, Arguments& a) {
    std::visit(
        [&](auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, canon::UseLengthUnits>) {
            const auto w = a.word();
            c.units = w == "CANON_UNITS_INCHES" ? canon::Units::Inches
                      : w == "CANON_UNITS_CM"   ? canon::Units::Centimetres
                                                : canon::Units::Millimetres;
          } else if constexpr (std::is_same_v<T, canon::SetOriginOffsets>) {
            c.offset = {a.next(), a.next(), a.next()};
            if (a.left() >= 3) c.rotary = canon::Rotary{a.next(), a.next(), a.next()};
          } else if constexpr (std::is_same_v<T, canon::SetFeedReference>) {
            c.reference = a.word() == "CANON_WORKPIECE" ? canon::FeedReference::Workpiece
                                                        : canon::FeedReference::Xyz;
          } else if constexpr (std::is_same_v<T, canon::SelectPlane>) {
            const auto w = a.word();
            c.plane = w == "CANON_PLANE_YZ"   ? canon::Plane::Yz
                      : w == "CANON_PLANE_XZ" ? canon::Plane::Xz
                                              : canon::Plane::Xy;
            plane = c.plane;
          } else if constexpr (std::is_same_v<T, canon::StraightTraverse> ||
                               std::is_same_v<T, canon::StraightFeed>) {
            c.to = a.pose();
          } else if constexpr (std::is_same_v<T, canon::ArcFeed>) {
            if (name == "ARC_FEED_3D") {
              c.end.x = a.next(), c.end.y = a.next(), c.end.z = a.next();
              c.centre = {a.next(), a.next(), a.next()};
              c.normal = {a.next(), a.next(), a.next()};
              c.turns = a.whole();
            } else {
              canon::PlaneArc p{plane};
              p.first_end = a.next(), p.second_end = a.next();
              p.first_axis = a.next(), p.second_axis = a.next();
              p.rotation = a.whole();
              p.axis_end_point = a.next();
              c = canon::arc_from_plane(p);
            }
            if (c.turns == 0) c.turns = 1;  // never 0 (call.hpp)
            a.tail(c.end.rotary, c.end.tool_axis);
          } else if constexpr (std::is_same_v<T, canon::NurbsFeed>) {
            c.degree = a.whole();
            for (const auto point : split_arguments(strip(a.word()))) {
              if (c.points.size() == 64) break;
              Arguments p{split_arguments(strip(point))};
              c.points.push_back({p.next(), p.next(), p.next(), p.left() ? p.next() : 1.0});
            }
            Arguments knots{split_arguments(strip(a.word()))};
            while (knots.left() > 0 && c.knots.size() < 128) c.knots.push_back(knots.next());
            a.tail(c.rotary, c.tool_axis);
          } else if constexpr (std::is_same_v<T, canon::SetFeedRate>) {
            c.rate = a.next();
          } else if constexpr (std::is_same_v<T, canon::SetSpindleSpeed>) {
            c.rpm = a.next();
          } else if constexpr (std::is_same_v<T, canon::SelectTool> ||
                               std::is_same_v<T, canon::ChangeTool>) {
            c.slot = static_cast<std::int32_t>(
                std::strtol(std::string(a.word().substr(0, 20)).c_str(), nullptr, 10));
          } else if constexpr (std::is_same_v<T, canon::UseToolLengthOffset>) {
            c.length = a.next();
          } else if constexpr (std::is_same_v<T, canon::Dwell>) {
            c.seconds = a.next();
          } else if constexpr (std::is_same_v<T, canon::Comment> ||
                               std::is_same_v<T, canon::Message>) {
            c.text = unquote(a.word());
          } else if constexpr (std::is_same_v<T, canon::Begin>) {
            c.entity = entity(a);
            while (a.left() > 0) {
              const auto option = a.word();
              const auto eq = option.find('=');
              if (eq != std::string_view::npos)
                (void)canon::set_output_option(c.options, option.substr(0, eq),
                                               option.substr(eq + 1));
            }
          } else if constexpr (std::is_same_v<T, canon::End>) {
            c.entity = entity(a);
          } else if constexpr (std::is_same_v<T, canon::Cycle>) {
            c.x = a.next(), c.y = a.next(), c.safe_z = a.next(), c.r_z = a.next();
            c.bottom_z = a.next(), c.feed = a.next(), c.dwell = a.next();
            if (c.kind == canon::CycleKind::PeckDrill) {
              c.peck = a.next(), c.peck_retract = a.next(), c.peck_clearance = a.next();
            } else if (c.kind == canon::CycleKind::Tap) {
              c.pitch = a.next(), c.spindle_speed = a.next();
              c.left_hand = a.word() == "LEFT_HAND";
            } else if (c.kind == canon::CycleKind::Bore) {
              c.spindle_stop = a.word() == "SPINDLE_STOP";
            }
            a.tail(c.rotary, c.tool_axis);
          }
        },
        call);
  }

  static std::string_view strip(std::string_view s) {
    if (s.size() >= 2 && (s.front() == '[' || s.front() == '(')) return s.substr(1, s.size() - 2);
    return s;
  }
};

// The calls of a trace text, at most kMaxCalls.
constexpr std::size_t kMaxCalls = 4000;

std::vector<canon::Call> decode(std::string_view text) {
  std::vector<canon::Call> calls;
  Decoder decoder;
  while (!text.empty() && calls.size() < kMaxCalls) {
    const std::size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
    while (!line.empty() && (line.front() == ' ' || (line.front() >= '0' && line.front() <= '9')))
      line.remove_prefix(1);
    const std::size_t open = line.find('(');
    const std::size_t close = line.rfind(')');
    if (open == std::string_view::npos) continue;
    const std::string_view name = line.substr(0, open);
    const auto known = calls_by_name().find(name);
    if (known == calls_by_name().end()) continue;
    canon::Call call = known->second;
    Arguments arguments{split_arguments(line.substr(
        open + 1, close == std::string_view::npos || close < open ? std::string_view::npos
                                                                  : close - open - 1))};
    decoder.fill(call, name, arguments);
    calls.push_back(std::move(call));
  }
  return calls;
}

bool has_tool_axis(const canon::Call& call) {
  return std::visit(
      [](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, canon::StraightTraverse> ||
                      std::is_same_v<T, canon::StraightFeed>)
          return c.to.tool_axis.has_value();
        else if constexpr (std::is_same_v<T, canon::ArcFeed>)
          return c.end.tool_axis.has_value();
        else if constexpr (std::is_same_v<T, canon::NurbsFeed> || std::is_same_v<T, canon::Cycle>)
          return c.tool_axis.has_value();
        else
          return false;
      },
      call);
}

// ---- rendering -----------------------------------------------------------------------------

const ncpost::profile::LoadedProfile& profile(std::string_view id) {
  static ncpost::profile::ProfileStore store = [] {
    ncpost::xslt::initialise();
    return ncpost::profile::ProfileStore(NCPOST_STYLESHEETS_DIR);
  }();
  static std::map<std::string, std::shared_ptr<const ncpost::profile::LoadedProfile>, std::less<>>
      loaded;
  auto& p = loaded[std::string(id)];
  if (!p) {
    std::vector<ncpost::diag::FileDiagnostic> diagnostics;
    p = store.load(id, diagnostics);
    if (!p) __builtin_trap();  // a built-in profile that does not load is the harness's bug
  }
  return *p;
}

void render(std::string_view id, const std::vector<canon::Call>& calls) {
  ncpost::render::RenderOptions options;
  options.batch_delay = std::chrono::milliseconds{0};  // the same batches on every run
  std::size_t bytes = 0;
  ncpost::render::Renderer renderer(
      profile(id), [&](std::string_view s) { bytes += s.size(); }, options, "fuzz");
  for (const auto& call : calls) renderer.call(call);
  renderer.finish();
  bool error = false;
  for (const auto& d : renderer.diagnostics())
    error = error || d.diagnostic.severity == ncpost::diag::Severity::Error;
  if (renderer.failed() && !error) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto calls = decode(std::string_view(reinterpret_cast<const char*>(data), size));
  render("linuxcnc", calls);
  for (const auto& call : calls) {
    if (has_tool_axis(call)) {
      render("linuxcnc-5ax", calls);
      break;
    }
  }
  return 0;
}
