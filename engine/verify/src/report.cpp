// The verifier's report, as text (one line per feature) and as JSON (everything).

#include <cstdio>
#include <nlohmann/json.hpp>

#include "ncpost/diag/json.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::verify {
namespace {

std::string fmt(double v, int decimals = 4) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  std::string s = buffer;
  if (s.find_first_not_of("-0.") == std::string::npos && s.front() == '-') s.erase(0, 1);
  return s;
}
std::string fmt(const Position& p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ", " + fmt(p.z) + ")";
}

std::size_t errors(const VerifyResult& r) {
  std::size_t n = 0;
  for (const auto& d : r.interpreter) n += d.severity == diag::Severity::Error;
  for (const auto& f : r.findings) n += f.diagnostic.severity == diag::Severity::Error;
  return n;
}

nlohmann::ordered_json position_json(const Position& p) {
  return {{"x", p.x}, {"y", p.y}, {"z", p.z}};
}

}  // namespace

std::string format_text(const VerifyResult& r, std::string_view file) {
  std::string out = "verify " + std::string(file) + ": " + std::to_string(r.workingsteps) +
                    " workingsteps, " + std::to_string(r.motions) + " motions, tolerance " +
                    fmt(r.tolerance) + " mm\n";
  for (const FeatureReport& f : r.features) {
    out += "feature #" + std::to_string(f.id) + " " + f.type + " '" + f.name + "' (" +
           std::to_string(f.workingsteps) + " workingstep" + (f.workingsteps == 1 ? "" : "s") +
           "): ";
    if (!f.checked) {
      out += "not checked: " + f.not_checked_reason + "\n";
      continue;
    }
    out += "depth " + fmt(f.target_z) + (f.through ? " (through)" : "") + " " +
           (f.depth_reached ? "reached" : "NOT reached");
    if (f.deepest) out += " (deepest " + fmt(f.deepest->z) + ")";
    if (f.coverage_checked) {
      out += "; floor coverage " + fmt(100 * (1 - f.uncovered_fraction), 2) + "% of " +
             fmt(f.reachable_area, 1) + " mm2 reachable by radius " + fmt(f.tool_radius) +
             " (grid " + fmt(f.grid) + " mm";
      if (f.unreachable_area > 0) out += ", " + fmt(f.unreachable_area, 1) + " mm2 unreachable";
      out += ")";
      if (f.uncovered_sample) out += ", uncovered e.g. at " + fmt(*f.uncovered_sample);
    } else {
      out += "; floor coverage not measured (no tool radius)";
    }
    out += "\n";
  }
  out += "rapids below the security plane over the stock but clear of material: " +
         std::to_string(r.rapids_below_secplane_in_air) + "\n";
  const std::size_t n = errors(r);
  if (r.cancelled) return out + "result: cancelled (the checks are incomplete)\n";
  out += n == 0 ? std::string("result: pass\n")
                : "result: FAIL (" + std::to_string(n) + " error" + (n == 1 ? "" : "s") + ")\n";
  return out;
}

std::string format_json(const VerifyResult& r, std::string_view file) {
  nlohmann::ordered_json doc;
  doc["file"] = std::string(file);
  doc["ok"] = r.ok();
  if (r.cancelled) doc["cancelled"] = true;
  doc["tolerance"] = r.tolerance;
  doc["workingsteps"] = r.workingsteps;
  doc["motions"] = r.motions;
  doc["calls"] = r.calls;
  doc["rapids_below_secplane_in_air"] = r.rapids_below_secplane_in_air;
  auto& features = doc["features"] = nlohmann::ordered_json::array();
  for (const FeatureReport& f : r.features) {
    nlohmann::ordered_json j{{"id", f.id},
                             {"type", f.type},
                             {"name", f.name},
                             {"checked", f.checked},
                             {"workingsteps", f.workingsteps}};
    if (!f.checked) {
      j["reason"] = f.not_checked_reason;
    } else {
      j["floor_z"] = f.floor_z;
      j["target_z"] = f.target_z;
      j["through"] = f.through;
      j["depth_reached"] = f.depth_reached;
      if (f.deepest) j["deepest"] = position_json(*f.deepest);
      if (f.coverage_checked) {
        nlohmann::ordered_json c{{"grid", f.grid},
                                 {"tool_radius", f.tool_radius},
                                 {"reachable_mm2", f.reachable_area},
                                 {"unreachable_mm2", f.unreachable_area},
                                 {"uncovered_fraction", f.uncovered_fraction}};
        if (f.uncovered_sample) c["uncovered_sample"] = position_json(*f.uncovered_sample);
        j["coverage"] = std::move(c);
      }
    }
    features.push_back(std::move(j));
  }
  auto& diagnostics = doc["diagnostics"] = nlohmann::ordered_json::array();
  const auto diagnostic = [](const diag::Diagnostic& d) { return diag::to_json(d); };
  for (const auto& d : r.interpreter) diagnostics.push_back(diagnostic(d));
  for (const Finding& f : r.findings) {
    nlohmann::ordered_json j = diagnostic(f.diagnostic);
    if (f.workingstep != 0)
      j["workingstep"] = {{"id", f.workingstep}, {"name", f.workingstep_name}};
    if (f.feature != 0) j["feature"] = f.feature;
    if (f.position) j["position"] = position_json(*f.position);
    if (f.motion != 0) j["motion"] = f.motion;
    if (f.trace_line != 0) j["trace_line"] = f.trace_line;
    diagnostics.push_back(std::move(j));
  }
  return doc.dump(2) + "\n";
}

}  // namespace ncpost::verify
