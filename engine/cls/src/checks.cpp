// The `checks` section: validated by hand against the rules of $defs/checks in
// stylesheets/profile.schema.json (tests/unit/cls/checks_test.cpp walks the schema to hold both
// to the same rules), patterns compiled with RE2; and the checks themselves (CheckRun).

#include "ncpost/cls/checks.hpp"

#include <re2/re2.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "check_run.hpp"
#include "ncpost/diag/json.hpp"
#include "records.hpp"

namespace ncpost::cls {
namespace {

using nlohmann::json;

class Validator {
 public:
  explicit Validator(std::vector<diag::Diagnostic>& out) : out_(out) {}

  void fail(const std::string& path, const std::string& message) {
    ok_ = false;
    out_.push_back(
        diag::make(diag::Code::ClsChecksInvalid, 0, 0, "checks" + path + ": " + message));
  }
  [[nodiscard]] bool ok() const noexcept { return ok_; }

  bool object(const json& node, const std::string& path,
              std::initializer_list<std::string_view> allowed) {
    if (!node.is_object()) {
      fail(path, "must be an object");
      return false;
    }
    for (const auto& [key, value] : node.items()) {
      bool known = false;
      for (auto a : allowed) known = known || a == key;
      if (!known) fail(path + "/" + key, "unknown field");
    }
    return true;
  }
  std::optional<bool> boolean(const json& node, const std::string& path) {
    if (!node.is_boolean()) {
      fail(path, "must be true or false");
      return std::nullopt;
    }
    return node.get<bool>();
  }
  std::optional<double> number(const json& node, const std::string& path, double min, double max,
                               bool exclusive_min = false) {
    if (!node.is_number()) {
      fail(path, "must be a number");
      return std::nullopt;
    }
    const double v = node.get<double>();
    if (!std::isfinite(v) || v < min || v > max || (exclusive_min && v <= min)) {
      fail(path, "out of range");
      return std::nullopt;
    }
    return v;
  }
  std::optional<std::string> string(const json& node, const std::string& path,
                                    std::size_t min_length, std::size_t max_length) {
    if (!node.is_string()) {
      fail(path, "must be a string");
      return std::nullopt;
    }
    auto s = node.get<std::string>();
    if (s.size() < min_length || s.size() > max_length) {
      fail(path,
           "length must be " + std::to_string(min_length) + ".." + std::to_string(max_length));
      return std::nullopt;
    }
    return s;
  }
  bool array(const json& node, const std::string& path, std::size_t min_items,
             std::size_t max_items) {
    if (!node.is_array()) {
      fail(path, "must be an array");
      return false;
    }
    if (node.size() < min_items || node.size() > max_items) {
      fail(path,
           "must have " + std::to_string(min_items) + ".." + std::to_string(max_items) + " items");
      return false;
    }
    return true;
  }
  std::shared_ptr<const re2::RE2> regex(const json& node, const std::string& path) {
    auto text = string(node, path, 1, kMaxRegexBytes);
    if (!text) return nullptr;
    re2::RE2::Options options;
    options.set_log_errors(false);
    auto compiled = std::make_shared<const re2::RE2>(*text, options);
    if (!compiled->ok()) {
      fail(path, "does not compile: " + compiled->error());
      return nullptr;
    }
    return compiled;
  }

 private:
  std::vector<diag::Diagnostic>& out_;
  bool ok_ = true;
};

void read_tool_names(Validator& v, const json& node, CheckConfig& config) {
  const std::string path = "/tool_names";
  if (!v.object(node, path, {"tolerance", "unmatched", "patterns"})) return;
  if (node.contains("tolerance"))
    if (auto t = v.number(node["tolerance"], path + "/tolerance", 0, 1000)) config.tolerance = *t;
  if (node.contains("unmatched")) {
    if (auto u = v.string(node["unmatched"], path + "/unmatched", 1, 16)) {
      if (*u == "ignore")
        config.unmatched = Unmatched::Ignore;
      else if (*u == "warning")
        config.unmatched = Unmatched::Warning;
      else if (*u == "error")
        config.unmatched = Unmatched::Error;
      else
        v.fail(path + "/unmatched", "must be one of ignore, warning, error");
    }
  }
  if (!node.contains("patterns")) {
    v.fail(path + "/patterns", "missing (required)");
    return;
  }
  const json& patterns = node["patterns"];
  if (!v.array(patterns, path + "/patterns", 1, kMaxPatterns)) return;
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    const std::string here = path + "/patterns/" + std::to_string(i);
    const json& p = patterns[i];
    if (!v.object(p, here, {"regex", "ball", "diameter", "corner_radius", "length"})) continue;
    ToolNamePattern pattern;
    if (!p.contains("regex")) {
      v.fail(here + "/regex", "missing (required)");
      continue;
    }
    pattern.regex = v.regex(p["regex"], here + "/regex");
    if (pattern.regex) pattern.regex_text = pattern.regex->pattern();
    if (p.contains("ball"))
      if (auto b = v.boolean(p["ball"], here + "/ball")) pattern.ball = *b;
    if (p.contains("diameter"))
      pattern.fixed.diameter = v.number(p["diameter"], here + "/diameter", 0, 1e6);
    if (p.contains("corner_radius"))
      pattern.fixed.corner_radius = v.number(p["corner_radius"], here + "/corner_radius", 0, 1e6);
    if (p.contains("length"))
      pattern.fixed.length = v.number(p["length"], here + "/length", 0, 1e6);
    config.tool_patterns.push_back(std::move(pattern));
  }
}

void read_heads(Validator& v, const json& node, CheckConfig& config) {
  const std::string path = "/heads";
  if (!v.object(node, path, {"tolerance", "types", "default"})) return;
  if (node.contains("tolerance"))
    if (auto t = v.number(node["tolerance"], path + "/tolerance", 0, 1)) config.axis_tolerance = *t;
  if (!node.contains("types")) {
    v.fail(path + "/types", "missing (required)");
    return;
  }
  const json& types = node["types"];
  if (!types.is_object()) {
    v.fail(path + "/types", "must be an object");
    return;
  }
  if (types.empty() || types.size() > kMaxHeads)
    v.fail(path + "/types", "must have 1.." + std::to_string(kMaxHeads) + " head types");
  for (const auto& [name, ks] : types.items()) {
    const std::string here = path + "/types/" + name;
    if (name.empty() || name.size() > 64) v.fail(here, "a head name has 1..64 characters");
    if (!v.array(ks, here, 1, kMaxAllowedK)) continue;
    HeadType head{name, {}};
    for (std::size_t i = 0; i < ks.size(); ++i)
      if (auto k = v.number(ks[i], here + "/" + std::to_string(i), -1, 1))
        head.allowed_k.push_back(*k);
    config.heads.push_back(std::move(head));
  }
  if (node.contains("default")) {
    if (auto d = v.string(node["default"], path + "/default", 1, 64)) {
      if (!types.is_object() || !types.contains(*d))
        v.fail(path + "/default", "names no head type of /heads/types");
      config.default_head = *d;
    }
  }
}

void read_rules(Validator& v, const json& node, CheckConfig& config, const json* heads) {
  const std::string path = "/operation_rules";
  if (!v.array(node, path, 0, kMaxRules)) return;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string here = path + "/" + std::to_string(i);
    const json& r = node[i];
    if (!v.object(r, here, {"match", "head", "options"})) continue;
    OperationRule rule;
    if (!r.contains("match")) {
      v.fail(here + "/match", "missing (required)");
      continue;
    }
    rule.regex = v.regex(r["match"], here + "/match");
    if (rule.regex) rule.regex_text = rule.regex->pattern();
    if (r.contains("head")) {
      if (auto h = v.string(r["head"], here + "/head", 1, 64)) {
        const bool known = heads && heads->is_object() && heads->contains("types") &&
                           (*heads)["types"].is_object() && (*heads)["types"].contains(*h);
        if (!known) v.fail(here + "/head", "names no head type of /heads/types");
        rule.head = *h;
      }
    }
    if (r.contains("options")) {
      const json& options = r["options"];
      if (!options.is_object()) {
        v.fail(here + "/options", "must be an object");
      } else if (options.size() > kMaxOptionsPerRule) {
        v.fail(here + "/options", "at most " + std::to_string(kMaxOptionsPerRule) + " options");
      } else {
        for (const auto& [key, value] : options.items()) {
          if (key.empty() || key.size() > 64) v.fail(here + "/options/" + key, "1..64 characters");
          if (auto s = v.string(value, here + "/options/" + key, 0, 200)) {
            // Known options and values only (profile loading says the same, PROFILE-010).
            if (const std::string problem = canon::set_output_option(rule.output, key, *s);
                !problem.empty())
              v.fail(here + "/options/" + key, problem);
            rule.options.emplace_back(key, *s);
          }
        }
      }
    }
    if (!r.contains("head") && !r.contains("options"))
      v.fail(here, "gives neither head nor options");
    config.operation_rules.push_back(std::move(rule));
  }
}

std::optional<double> group_number(std::string_view text) {
  if (text.empty()) return std::nullopt;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

}  // namespace

const HeadType* CheckConfig::head(std::string_view name) const noexcept {
  for (const auto& h : heads)
    if (h.name == name) return &h;
  return nullptr;
}

std::optional<CheckConfig> parse_checks(const json& section,
                                        std::vector<diag::Diagnostic>& diagnostics) {
  Validator v(diagnostics);
  CheckConfig config;
  if (!v.object(section, "", {"enabled", "tool_names", "heads", "operation_rules"}))
    return std::nullopt;
  if (section.contains("enabled"))
    if (auto e = v.boolean(section["enabled"], "/enabled")) config.enabled = *e;
  if (section.contains("tool_names")) read_tool_names(v, section["tool_names"], config);
  if (section.contains("heads")) read_heads(v, section["heads"], config);
  if (section.contains("operation_rules"))
    read_rules(v, section["operation_rules"], config,
               section.contains("heads") ? &section["heads"] : nullptr);
  if (!v.ok()) return std::nullopt;
  return config;
}

std::optional<CheckConfig> parse_checks(std::string_view json_text,
                                        std::vector<diag::Diagnostic>& diagnostics) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    diagnostics.push_back(
        diag::json_syntax_error(diag::Code::ClsChecksInvalid, json_text, e, "checks: "));
    return std::nullopt;
  }
  return parse_checks(doc, diagnostics);
}

std::optional<ToolDimensions> dimensions_from_name(const CheckConfig& config,
                                                   std::string_view tool_name) {
  for (const auto& pattern : config.tool_patterns) {
    if (!pattern.regex) continue;
    const re2::RE2& re = *pattern.regex;
    const int groups = re.NumberOfCapturingGroups();
    std::vector<re2::StringPiece> captured(static_cast<std::size_t>(groups) + 1);
    if (!re.Match(re2::StringPiece(tool_name.data(), tool_name.size()), 0, tool_name.size(),
                  re2::RE2::UNANCHORED, captured.data(), groups + 1))
      continue;
    ToolDimensions d = pattern.fixed;
    for (const auto& [name, index] : re.NamedCapturingGroups()) {
      const re2::StringPiece& piece = captured[static_cast<std::size_t>(index)];
      if (piece.data() == nullptr) continue;  // an optional group that did not take part
      const auto value = group_number(std::string_view(piece.data(), piece.size()));
      if (!value) continue;
      if (name == "diameter") d.diameter = value;
      if (name == "corner_radius") d.corner_radius = value;
      if (name == "length") d.length = value;
    }
    if (pattern.ball && d.diameter && !d.corner_radius) d.corner_radius = *d.diameter / 2;
    return d;
  }
  return std::nullopt;
}

namespace detail {

CheckRun::CheckRun(const CheckConfig& config, Report report)
    : config_(config), report_(std::move(report)) {}

void CheckRun::select(const std::pair<std::string, std::string>& option) {
  for (const auto& s : selected_)
    if (s == option) return;
  selected_.push_back(option);
}

canon::OutputOptions CheckRun::operation(std::string_view name, std::uint32_t line) {
  end_operation();
  canon::OutputOptions output;
  operation_.assign(name);
  operation_line_ = line;
  head_ = config_.default_head.empty() ? nullptr : config_.head(config_.default_head);
  bool head_chosen = false;
  for (const auto& rule : config_.operation_rules) {
    if (!rule.regex ||
        !re2::RE2::PartialMatch(re2::StringPiece(name.data(), name.size()), *rule.regex))
      continue;
    if (!rule.head.empty() && !head_chosen) {
      head_ = config_.head(rule.head);
      head_chosen = true;
    }
    for (const auto& option : rule.options) select(option);
    canon::add_unset(output, rule.output);
  }
  return output;
}

void CheckRun::tool_name(std::string_view name, std::uint32_t line, std::uint32_t column) {
  tool_name_.assign(name);
  tool_name_line_ = line;
  tool_name_column_ = column;
  tool_data_seen_ = false;
  from_name_ = dimensions_from_name(config_, name);
  if (!from_name_ && config_.unmatched != Unmatched::Ignore && !config_.tool_patterns.empty()) {
    auto d = diag::make(diag::Code::ClsCheckUnmatchedName, line, column,
                        "tool name '" + tool_name_ + "' matches none of the shop's tool-name " +
                            "patterns (checks.tool_names.patterns)");
    if (config_.unmatched == Unmatched::Error) d.severity = diag::Severity::Error;
    report_(std::move(d));
  }
}

void CheckRun::tool_data(const ToolDimensions& data, std::string_view word, std::uint32_t line) {
  tool_data_seen_ = true;
  if (!from_name_) return;
  auto compare = [&](const std::optional<double>& named, const std::optional<double>& stated,
                     const char* what) {
    if (!named || !stated || std::fabs(*named - *stated) <= config_.tolerance) return;
    report_(diag::make(diag::Code::ClsCheckToolName, line, 1,
                       std::string(what) + ": tool name '" + tool_name_ + "' (line " +
                           std::to_string(tool_name_line_) + ") says " +
                           detail::format_number(*named) + ", " + std::string(word) + "/ (line " +
                           std::to_string(line) + ") says " + detail::format_number(*stated)));
  };
  compare(from_name_->diameter, data.diameter, "diameter");
  compare(from_name_->corner_radius, data.corner_radius, "corner radius");
  compare(from_name_->length, data.length, "length");
}

void CheckRun::tool_axis(const canon::Direction& axis, std::uint32_t line, std::uint32_t column) {
  if (!head_ || axis_reported_) return;
  const double norm = std::sqrt(axis.i * axis.i + axis.j * axis.j + axis.k * axis.k);
  if (norm == 0) return;
  const double k = axis.k / norm;
  std::string allowed;
  for (double a : head_->allowed_k) {
    if (std::fabs(k - a) <= config_.axis_tolerance) return;
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.7f", a);
    allowed += (allowed.empty() ? "" : ", ") + std::string(buffer);
  }
  axis_reported_ = true;
  char value[32];
  std::snprintf(value, sizeof value, "%.7f", k);
  report_(diag::make(diag::Code::ClsCheckToolAxis, line, column,
                     "tool axis k = " + std::string(value) + " here, but operation '" + operation_ +
                         "' (line " + std::to_string(operation_line_) + ") runs on head '" +
                         head_->name + "', which allows k = " + allowed));
}

void CheckRun::end_operation() {
  if (from_name_ && !tool_data_seen_ &&
      (from_name_->diameter || from_name_->corner_radius || from_name_->length))
    report_(diag::make(diag::Code::ClsCheckNoToolData, tool_name_line_, tool_name_column_,
                       "tool name '" + tool_name_ +
                           "' states dimensions, but the operation has no TLDATA/ or CUTTER/ "
                           "to check them against"));
  from_name_.reset();
  tool_data_seen_ = false;
  tool_name_.clear();
  axis_reported_ = false;
  head_ = nullptr;
  operation_.clear();
}

}  // namespace detail
}  // namespace ncpost::cls
