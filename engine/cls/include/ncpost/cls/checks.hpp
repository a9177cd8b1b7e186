#pragma once
// The shop's pre-post checks of a CL file, configured per machine in profile.json's `checks`
// section (stylesheets/profile.schema.json, $defs/checks; docs/cls.md, "Pre-post checks").
//
// In:  the section as JSON (the profile carries it raw: profile::Profile::checks_json).
// Out: a CheckConfig for cls::ReadOptions::checks, or nullopt with CLS-100 diagnostics naming
//      the JSON path of each problem. The reader runs the checks while it reads; each failed
//      check is an error with the CL line and the two values that disagree.

#include <cstddef>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncpost/canon/output_options.hpp"
#include "ncpost/diag/diagnostic.hpp"

namespace re2 {
class RE2;
}

namespace ncpost::cls {

// What a tool name or a tool record says about the tool (program length units).
struct ToolDimensions {
  std::optional<double> diameter;
  std::optional<double> corner_radius;
  std::optional<double> length;
};

// A tool-name pattern: an RE2 expression whose named groups `diameter`, `corner_radius` and
// `length` capture numbers (e.g. ^T\d+-D(?P<diameter>[\d.]+)(?:-CR(?P<corner_radius>[\d.]+))?$),
// plus values every matching name implies (`fixed`, e.g. corner radius 0 for MILL-20) and
// `ball` (a ball mill: corner radius = diameter / 2, for BALL-50).
struct ToolNamePattern {
  std::string regex_text;
  std::shared_ptr<const re2::RE2> regex;
  ToolDimensions fixed;
  bool ball = false;
};

enum class Unmatched : std::uint8_t { Ignore, Warning, Error };

// A head type and the tool-axis k components it can take (straight: 1, 30° head: 0.8660254,
// 90° head: 0), compared within CheckConfig::axis_tolerance after normalising the axis.
struct HeadType {
  std::string name;
  std::vector<double> allowed_k;
};

// An operation-name rule: when `regex` finds a match in a TOOL PATH/ operation name, the
// operation uses `head` (when not empty) and selects `options` for the renderer.
struct OperationRule {
  std::string regex_text;
  std::shared_ptr<const re2::RE2> regex;
  std::string head;
  std::vector<std::pair<std::string, std::string>> options;
  canon::OutputOptions output;  // the same options, typed (canon/output_options.hpp)
};

// Sizes the section may have (every limit named; the schema states the same).
inline constexpr std::size_t kMaxPatterns = 64;
inline constexpr std::size_t kMaxRules = 64;
inline constexpr std::size_t kMaxHeads = 32;
inline constexpr std::size_t kMaxAllowedK = 16;
inline constexpr std::size_t kMaxOptionsPerRule = 32;
inline constexpr std::size_t kMaxRegexBytes = 1000;

struct CheckConfig {
  // false: the section is kept but no check runs (the profile's own off switch).
  bool enabled = true;
  // Tool name vs TLDATA/ / CUTTER/: how far a dimension may differ (program length units).
  double tolerance = 0.01;
  Unmatched unmatched = Unmatched::Ignore;
  std::vector<ToolNamePattern> tool_patterns;
  // Tool axis vs head.
  double axis_tolerance = 1e-6;
  std::vector<HeadType> heads;
  std::string default_head;  // empty: operations no rule gives a head are not checked
  std::vector<OperationRule> operation_rules;

  [[nodiscard]] const HeadType* head(std::string_view name) const noexcept;
};

// Validates and compiles the section; nullopt with CLS-100 diagnostics when anything is wrong.
[[nodiscard]] std::optional<CheckConfig> parse_checks(const nlohmann::json& section,
                                                      std::vector<diag::Diagnostic>& diagnostics);
// The same from JSON text (profile::Profile::checks_json); CLS-100 also for text that is not JSON.
[[nodiscard]] std::optional<CheckConfig> parse_checks(std::string_view json_text,
                                                      std::vector<diag::Diagnostic>& diagnostics);

// What a name says under the config's patterns: the first pattern that matches decides; nullopt
// when none does. Values a group captured that are not numbers are left out.
[[nodiscard]] std::optional<ToolDimensions> dimensions_from_name(const CheckConfig& config,
                                                                 std::string_view tool_name);

}  // namespace ncpost::cls
