// Technology units cross-checked (units.hpp).

#include "units.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>

namespace ncpost::stepnc::units {
namespace {

// A number for a message: up to 4 significant decimals, trailing zeros dropped.
std::string fmt(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", x);
  std::string s = buffer;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

bool agree(double a, double b) {
  return a > 0 && b > 0 && a <= b * kAgreement && b <= a * kAgreement;
}

// The tool's surface speed (m/s) at `rpm`.
double surface_speed(double diameter, double rpm) {
  return std::numbers::pi * diameter * rpm / 60000.0;
}

bool plausible_rpm(double rpm, double diameter) {
  const double v = surface_speed(diameter, rpm);
  return rpm <= kMaxRpm && v >= kMinSurfaceSpeed && v <= kMaxSurfaceSpeed;
}

// The spindle: against the cutting speed when both are written, else on its own.
void check_spindle(const Written& w, double diameter, Reading& out) {
  const double s = *w.spindle;
  const double iso_rpm = std::abs(s) * 60;  // ISO 14649: rev/s
  const double as_rpm = std::abs(s);        // written in rpm
  // Messages are made only when there is something to say (this runs per technology).
  const auto spindle_text = [&] { return "spindle " + fmt(s); };
  const auto tool_text = [&] { return " on a tool of diameter " + fmt(diameter) + " mm"; };
  if (w.cutspeed && *w.cutspeed > 0) {
    const double v = *w.cutspeed;
    // ISO units first; a pair agrees only at a plausible speed (a file that writes both in
    // "per minute" units agrees with itself in ISO units, at an absurd speed).
    for (const bool rpm : {false, true}) {
      for (const bool per_minute : {false, true}) {
        const double n = rpm ? as_rpm : iso_rpm;
        const double cut = per_minute ? v / 60 : v;
        if (!agree(surface_speed(diameter, n), cut) || !plausible_rpm(n, diameter)) continue;
        const std::string why =
            ": at " + fmt(n) + " rpm" + tool_text() + " the cutting speed is " + fmt(cut) + " m/s";
        if (rpm) {
          out.spindle = s / 60;
          out.notes.push_back(spindle_text() + " read as rpm (" + fmt(as_rpm) +
                              " rpm), not rev/s (" + fmt(iso_rpm) + " rpm)" + why);
        }
        if (per_minute)
          out.notes.push_back("cutspeed " + fmt(v) + " read as m/min (" + fmt(cut) +
                              " m/s), not m/s" + why);
        return;
      }
    }
    out.errors.push_back(spindle_text() + " (" + fmt(iso_rpm) + " rpm as rev/s, " + fmt(as_rpm) +
                         " as rpm)" + tool_text() + " cuts at " +
                         fmt(surface_speed(diameter, iso_rpm)) + " or " +
                         fmt(surface_speed(diameter, as_rpm)) + " m/s, but cutspeed is " + fmt(v) +
                         " (m/s, or m/min): no reading of the units makes them agree");
    return;
  }
  if (plausible_rpm(iso_rpm, diameter)) return;
  if (plausible_rpm(as_rpm, diameter)) {
    out.spindle = s / 60;
    out.notes.push_back(spindle_text() + " read as rpm (" + fmt(as_rpm) +
                        " rpm), not rev/s: " + fmt(iso_rpm) + " rpm" + tool_text() +
                        " would cut at " + fmt(surface_speed(diameter, iso_rpm)) + " m/s");
    return;
  }
  out.errors.push_back(spindle_text() + " is " + fmt(iso_rpm) + " rpm as rev/s and " + fmt(as_rpm) +
                       " rpm as rpm" + tool_text() + ": neither gives a surface speed between " +
                       fmt(kMinSurfaceSpeed) + " and " + fmt(kMaxSurfaceSpeed) + " m/s");
}

// The feed: against feed per tooth × teeth × spindle when all are known, else on its own.
void check_feed(const Written& w, const ToolSize& tool, Reading& out) {
  const double f = *w.feed;
  struct Unit {
    const char* name;
    double to_mm_per_min;
  };
  static constexpr Unit kUnits[] = {{"m/s", 60000}, {"mm/min", 1}, {"mm/s", 60}};
  const auto feed = [&] { return "feedrate " + fmt(f); };
  const auto take = [&](const Unit& u, const std::string& why) {
    out.feed = f * u.to_mm_per_min / 60000;
    out.notes.push_back(feed() + " read as " + u.name + " (" + fmt(f * u.to_mm_per_min) +
                        " mm/min), not m/s (" + fmt(f * 60000) + " mm/min): " + why);
  };
  const std::optional<double> spindle = out.spindle ? out.spindle : w.spindle;
  if (w.feed_per_tooth && *w.feed_per_tooth > 0 && tool.teeth && *tool.teeth > 0 && spindle &&
      *spindle != 0) {
    const double rpm = std::abs(*spindle) * 60;
    const double expected = *w.feed_per_tooth * *tool.teeth * rpm;
    const auto per_tooth = [&] {
      return "feedrate_per_tooth " + fmt(*w.feed_per_tooth) + " mm × " +
             std::to_string(*tool.teeth) + " teeth × " + fmt(rpm) + " rpm = " + fmt(expected) +
             " mm/min";
    };
    if (agree(f * kUnits[0].to_mm_per_min, expected)) return;
    for (std::size_t i = 1; i < std::size(kUnits); ++i)
      if (agree(f * kUnits[i].to_mm_per_min, expected)) return take(kUnits[i], per_tooth());
    out.errors.push_back(feed() + " (" + fmt(f * 60000) + " mm/min as m/s) disagrees with " +
                         per_tooth() + " in every unit (m/s, mm/min, mm/s)");
    return;
  }
  const auto plausible = [](double mm_per_min) {
    return mm_per_min >= kMinFeed && mm_per_min <= kMaxFeed;
  };
  if (plausible(f * kUnits[0].to_mm_per_min)) return;
  for (std::size_t i = 1; i < std::size(kUnits); ++i)
    if (plausible(f * kUnits[i].to_mm_per_min))
      return take(kUnits[i], "as m/s it is beyond " + fmt(kMaxFeed) + " mm/min");
  out.errors.push_back(feed() + " is " + fmt(f * 60000) + " mm/min as m/s and " + fmt(f) +
                       " as mm/min: neither lies between " + fmt(kMinFeed) + " and " +
                       fmt(kMaxFeed) + " mm/min");
}

}  // namespace

Reading cross_check(const Written& written, const ToolSize& tool) {
  Reading out;
  if (written.spindle && *written.spindle != 0 && std::isfinite(*written.spindle) &&
      tool.diameter && *tool.diameter > 0)
    check_spindle(written, *tool.diameter, out);
  if (written.feed && *written.feed > 0 && std::isfinite(*written.feed))
    check_feed(written, tool, out);
  if (!out.spindle) out.spindle = written.spindle;
  if (!out.feed) out.feed = written.feed;
  return out;
}

}  // namespace ncpost::stepnc::units
