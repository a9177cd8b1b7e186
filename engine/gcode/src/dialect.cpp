// dialect.json → Dialect, checked field by field against what stylesheets/dialect.schema.json
// says (tests/unit/gcode walks the schema and checks that every refusal agrees).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "lexer.hpp"
#include "ncpost/diag/json.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace ncpost::gcode {

WordId Dialect::word(std::string_view word_name) const noexcept {
  for (std::size_t i = 0; i < words.size(); ++i)
    if (words[i].name == word_name) return static_cast<WordId>(i);
  return kNoWord;
}

namespace {

using nlohmann::json;

// One problem per diagnostic, naming the JSON path.
class Checker {
 public:
  explicit Checker(std::vector<diag::Diagnostic>& out) : out_(out) {}
  void fail(const std::string& path, const std::string& message) {
    out_.push_back(diag::make(diag::Code::GcodeDialectInvalid, 0, 0,
                              (path.empty() ? "/" : path) + ": " + message));
  }
  [[nodiscard]] bool ok() const { return out_.empty(); }

  // The object's keys must be among `allowed`, and `required` must be there.
  bool object(const json& j, const std::string& path, std::initializer_list<const char*> allowed,
              std::initializer_list<const char*> required) {
    if (!j.is_object()) {
      fail(path, "must be an object");
      return false;
    }
    for (const auto& item : j.items()) {
      // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
      const std::string& key = item.key();
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }))
        fail(path + "/" + key, "unknown field");
    }
    bool all = true;
    for (const char* r : required)
      if (!j.contains(r)) {
        fail(path + "/" + r, "required field missing");
        all = false;
      }
    return all;
  }
  std::optional<std::string> string(const json& j, const std::string& path) {
    if (!j.is_string()) {
      fail(path, "must be a string");
      return std::nullopt;
    }
    return j.get<std::string>();
  }
  std::optional<bool> boolean(const json& j, const std::string& path) {
    if (!j.is_boolean()) {
      fail(path, "must be true or false");
      return std::nullopt;
    }
    return j.get<bool>();
  }
  std::optional<double> number(const json& j, const std::string& path, double min, double max,
                               bool exclusive_min = false) {
    if (!j.is_number()) {
      fail(path, "must be a number");
      return std::nullopt;
    }
    const double v = j.get<double>();
    if ((exclusive_min ? v <= min : v < min) || v > max) {
      fail(path, "out of range");
      return std::nullopt;
    }
    return v;
  }
  std::optional<long long> integer(const json& j, const std::string& path, long long min,
                                   long long max) {
    if (!j.is_number_integer()) {
      fail(path, "must be an integer");
      return std::nullopt;
    }
    const auto v = j.get<long long>();
    if (v < min || v > max) {
      fail(path, "out of range");
      return std::nullopt;
    }
    return v;
  }
  template <typename E>
  std::optional<E> choice(const json& j, const std::string& path,
                          const std::vector<std::pair<const char*, E>>& values) {
    if (j.is_string()) {
      const auto s = j.get<std::string>();
      for (const auto& [name, value] : values)
        if (s == name) return value;
    }
    std::string list;
    for (const auto& [name, value] : values) {
      if (!list.empty()) list.append(", ");
      list.append(name);
    }
    fail(path, std::string("must be one of ").append(list));
    return std::nullopt;
  }

 private:
  std::vector<diag::Diagnostic>& out_;
};

const std::vector<std::pair<const char*, Action>>& action_names() {
  static const std::vector<std::pair<const char*, Action>> names = {
      {"none", Action::None},
      {"rapid", Action::Rapid},
      {"linear", Action::Linear},
      {"arc_cw", Action::ArcCw},
      {"arc_ccw", Action::ArcCcw},
      {"cycle", Action::Cycle},
      {"cycle_cancel", Action::CycleCancel},
      {"dwell", Action::Dwell},
      {"plane_xy", Action::PlaneXy},
      {"plane_xz", Action::PlaneXz},
      {"plane_yz", Action::PlaneYz},
      {"units_inch", Action::UnitsInch},
      {"units_mm", Action::UnitsMm},
      {"absolute", Action::Absolute},
      {"incremental", Action::Incremental},
      {"arc_centre_absolute", Action::ArcCentreAbsolute},
      {"arc_centre_incremental", Action::ArcCentreIncremental},
      {"feed_per_minute", Action::FeedPerMinute},
      {"feed_inverse_time", Action::FeedInverseTime},
      {"feed_per_revolution", Action::FeedPerRevolution},
      {"work_offset", Action::WorkOffset},
      {"work_offset_none", Action::WorkOffsetNone},
      {"machine_coordinates", Action::MachineCoordinates},
      {"set_coordinate_data", Action::SetCoordinateData},
      {"axis_offset", Action::AxisOffset},
      {"axis_offset_cancel", Action::AxisOffsetCancel},
      {"axis_offset_restore", Action::AxisOffsetRestore},
      {"local_offset", Action::LocalOffset},
      {"home", Action::Home},
      {"home2", Action::Home2},
      {"tool_length_offset", Action::ToolLengthOffset},
      {"tool_length_cancel", Action::ToolLengthCancel},
      {"cutter_comp_off", Action::CutterCompOff},
      {"retract_initial", Action::RetractInitial},
      {"retract_r", Action::RetractR},
      {"spindle_cw", Action::SpindleCw},
      {"spindle_ccw", Action::SpindleCcw},
      {"spindle_stop", Action::SpindleStop},
      {"tool_change", Action::ToolChange},
      {"set_tool", Action::SetTool},
      {"program_stop", Action::ProgramStop},
      {"optional_stop", Action::OptionalStop},
      {"program_end", Action::ProgramEnd},
      {"pallet_change", Action::PalletChange},
      {"mist_on", Action::MistOn},
      {"flood_on", Action::FloodOn},
      {"coolant_off", Action::CoolantOff},
      {"subprogram_call", Action::SubprogramCall},
      {"local_call", Action::LocalCall},
      {"subprogram_return", Action::SubprogramReturn},
      {"macro_call", Action::MacroCall},
      {"unsupported", Action::Unsupported},
      {"lathe", Action::Lathe},
      {"arc_through_point", Action::ArcThroughPoint},
      {"spline_b", Action::SplineB},
      {"spline_nurbs", Action::SplineNurbs},
      {"translate", Action::Translate},
      {"translate_add", Action::TranslateAdd},
      {"only_without_words", Action::OnlyWithoutWords},
      {"spindle_cw_coolant", Action::SpindleCwCoolant},
      {"spindle_ccw_coolant", Action::SpindleCcwCoolant},
      {"cycle_call", Action::CycleCall},
  };
  return names;
}

const std::vector<std::pair<const char*, Operator>> kOperators = {
    {"add", Operator::Add},        {"sub", Operator::Sub},      {"mul", Operator::Mul},
    {"div", Operator::Div},        {"mod", Operator::Mod},      {"pow", Operator::Pow},
    {"eq", Operator::Eq},          {"ne", Operator::Ne},        {"gt", Operator::Gt},
    {"ge", Operator::Ge},          {"lt", Operator::Lt},        {"le", Operator::Le},
    {"and", Operator::And},        {"or", Operator::Or},        {"xor", Operator::Xor},
    {"bit_and", Operator::BitAnd}, {"bit_or", Operator::BitOr}, {"bit_xor", Operator::BitXor},
    {"int_div", Operator::IntDiv},
};

const std::vector<std::pair<const char*, Function>> kFunctions = {
    {"sin", Function::Sin},       {"cos", Function::Cos},     {"tan", Function::Tan},
    {"asin", Function::Asin},     {"acos", Function::Acos},   {"atan", Function::Atan},
    {"atan2", Function::Atan2},   {"sqrt", Function::Sqrt},   {"abs", Function::Abs},
    {"round", Function::Round},   {"floor", Function::Fix},   {"ceil", Function::Fup},
    {"ln", Function::Ln},         {"exp", Function::Exp},     {"exists", Function::Exists},
    {"square", Function::Square}, {"trunc", Function::Trunc}, {"not", Function::Not},
    {"min", Function::Min},       {"max", Function::Max},     {"sign", Function::Sign},
    {"frac", Function::Frac},     {"log10", Function::Log10}, {"neg", Function::Neg},
    {"bin", Function::Bin},       {"bcd", Function::Bcd},     {"away", Function::Away},
    {"pow", Function::Pow},
};

const std::vector<std::pair<const char*, WordKind>> kWordKinds = {
    {"axis", WordKind::Axis},
    {"length", WordKind::Length},
    {"number", WordKind::Number},
    {"feed", WordKind::Feed},
    {"speed", WordKind::Speed},
    {"tool", WordKind::Tool},
    {"g", WordKind::GCode},
    {"m", WordKind::MCode},
    {"polar_radius", WordKind::PolarRadius},
    {"polar_angle", WordKind::PolarAngle},
    {"tool_offset", WordKind::ToolOffset},
    {"line_number", WordKind::LineNumber},
    {"program", WordKind::Program},
};

const std::vector<std::pair<const char*, CycleKind>> kCycleKinds = {
    {"drill", CycleKind::Drill},
    {"drill_dwell", CycleKind::DrillDwell},
    {"peck", CycleKind::Peck},
    {"chip_break", CycleKind::ChipBreak},
    {"tap", CycleKind::Tap},
    {"tap_left", CycleKind::TapLeft},
    {"bore", CycleKind::Bore},
    {"bore_stop", CycleKind::BoreStop},
    {"bore_dwell", CycleKind::BoreDwell},
};

const std::vector<std::pair<const char*, ParameterSource>> kSources = {
    {"machine", ParameterSource::Machine},
    {"position", ParameterSource::Position},
    {"machine_position", ParameterSource::MachinePosition},
    {"tool", ParameterSource::Tool},
    {"work_offset_index", ParameterSource::WorkOffsetIndex},
    {"work_offsets", ParameterSource::WorkOffsets},
    {"axis_offsets", ParameterSource::AxisOffsets},
    {"units", ParameterSource::Units},
};

// A letter, then up to seven letters, digits or underscores (X, CR, TURN, I1).
// A letter, then up to seven letters, digits or underscores (X, CR, TURN, I1).
bool valid_word_name(const std::string& s) {
  if (s.empty() || s.size() > 8 || s[0] < 'A' || s[0] > 'Z') return false;
  for (const char c : s)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

// "G38.2" → (false, 382); "M30" → (true, 30).
bool parse_code_key(const std::string& key, bool& m, int& number) {
  if (key.size() < 2 || (key[0] != 'G' && key[0] != 'M')) return false;
  m = key[0] == 'M';
  const std::string_view digits = std::string_view(key).substr(1);
  std::size_t dot = digits.find('.');
  auto all_digits = [](std::string_view s) {
    return !s.empty() && s.size() <= 4 &&
           std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const std::string_view whole = digits.substr(0, dot);
  if (!all_digits(whole)) return false;
  int w = 0;
  std::from_chars(whole.data(), whole.data() + whole.size(), w);
  if (m) {
    if (dot != std::string_view::npos) return false;
    number = w;
    return true;
  }
  int frac = 0;
  if (dot != std::string_view::npos) {
    const std::string_view f = digits.substr(dot + 1);
    if (f.size() != 1 || !all_digits(f)) return false;
    frac = f[0] - '0';
  }
  number = w * 10 + frac;
  return true;
}

std::vector<WordId> word_list(Checker& c, const Dialect& d, const json& j,
                              const std::string& path) {
  std::vector<WordId> out;
  if (!j.is_array()) {
    c.fail(path, "must be an array of word names");
    return out;
  }
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto name = c.string(j[i], path + "/" + std::to_string(i));
    if (!name) continue;
    const WordId w = d.word(*name);
    if (w == kNoWord || (name->size() == 1 && !d.letter_known[w]))
      c.fail(path + "/" + std::to_string(i), "'" + *name + "' is not a word of this dialect");
    else
      out.push_back(w);
  }
  return out;
}

void read_lexical(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/lexical";
  if (!c.object(j, p,
                {"comments", "spaces_in_words", "block_delete", "percent", "checksums",
                 "comment_commands"},
                {"comments", "spaces_in_words"}))
    return;
  if (j.contains("comments")) {
    const auto& cm = j["comments"];
    if (!cm.is_array()) {
      c.fail(p + "/comments", "must be an array");
    } else {
      d.parenthesis_comments = d.semicolon_comments = false;
      for (std::size_t i = 0; i < cm.size(); ++i) {
        const auto v = c.choice<int>(cm[i], p + "/comments/" + std::to_string(i),
                                     {{"parentheses", 0}, {"semicolon", 1}});
        if (v && *v == 0) d.parenthesis_comments = true;
        if (v && *v == 1) d.semicolon_comments = true;
      }
    }
  }
  if (j.contains("spaces_in_words"))
    if (auto v = c.boolean(j["spaces_in_words"], p + "/spaces_in_words")) d.ignore_whitespace = *v;
  if (j.contains("block_delete"))
    if (auto v = c.boolean(j["block_delete"], p + "/block_delete")) d.block_delete = *v;
  if (j.contains("percent"))
    if (auto v = c.boolean(j["percent"], p + "/percent")) d.percent_delimits = *v;
  if (j.contains("checksums"))
    if (auto v = c.boolean(j["checksums"], p + "/checksums")) d.checksums = *v;
  if (j.contains("comment_commands")) {
    const auto& cc = j["comment_commands"];
    if (!cc.is_object()) {
      c.fail(p + "/comment_commands", "must be an object");
    } else {
      for (const auto& [key, value] : cc.items()) {
        const auto v = c.choice<std::string>(
            value, p + "/comment_commands/" + key,
            {{"message", "message"}, {"debug", "debug"}, {"abort", "abort"}, {"ignore", "ignore"}});
        if (key.empty() || key.size() > 16) c.fail(p + "/comment_commands/" + key, "bad prefix");
        std::string up = key;
        for (char& ch : up) ch = detail::upper(ch);
        if (v) d.comment_commands[up] = *v;
      }
    }
  }
}

void read_words(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/words";
  if (!j.is_object()) {
    c.fail(p, "must be an object");
    return;
  }
  d.words.resize(26);
  for (int i = 0; i < 26; ++i)
    d.words[static_cast<std::size_t>(i)].name = std::string(1, char('A' + i));
  for (const auto& [name, value] : j.items()) {
    const std::string path = p + "/" + name;
    const bool polar = name == "@" || name == "^";
    if (!valid_word_name(name) && !polar) {
      c.fail(path, "a word name is 1 to 8 upper-case letters, or @ or ^");
      continue;
    }
    const auto kind = c.choice(value, path, kWordKinds);
    if (!kind) continue;
    if (polar != (*kind == WordKind::PolarRadius || *kind == WordKind::PolarAngle)) {
      c.fail(path, "@ and ^ are the polar words, and only they are");
      continue;
    }
    if (polar) {
      (*kind == WordKind::PolarRadius ? d.polar_radius : d.polar_angle) =
          static_cast<WordId>(d.words.size());
      d.words.push_back({name, *kind, false});
      continue;
    }
    if (name.size() == 1) {
      const auto w = letter_word(name[0]);
      d.words[w].kind = *kind;
      d.words[w].rotary = name == "A" || name == "B" || name == "C";
      d.letter_known[w] = true;
    } else {
      if (d.words.size() >= kMaxWords) {
        c.fail(path, "too many words (at most " + std::to_string(kMaxWords - 26) + " named ones)");
        continue;
      }
      d.words.push_back({name, *kind, false});
    }
  }
  for (const char letter : {'G', 'M'}) {
    const auto w = letter_word(letter);
    if (!d.letter_known[w] ||
        d.words[w].kind != (letter == 'G' ? WordKind::GCode : WordKind::MCode))
      c.fail(p + "/" + std::string(1, letter), "G and M must be declared as \"g\" and \"m\"");
  }
}

void read_parameters(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/parameters";
  if (!c.object(j, p,
                {"style", "count", "named", "vacant", "zero_read_only", "locals", "ranges",
                 "machine_names", "alarm", "stop_message", "assign_in_order"},
                {"style"}))
    return;
  auto& r = d.parameters;
  if (j.contains("style"))
    if (auto v = c.choice<ParameterStyle>(j["style"], p + "/style",
                                          {{"none", ParameterStyle::None},
                                           {"hash", ParameterStyle::Hash},
                                           {"r", ParameterStyle::R},
                                           {"q", ParameterStyle::Q}}))
      r.style = *v;
  if (j.contains("count"))
    if (auto v = c.integer(j["count"], p + "/count", 1, 1000000))
      r.count = static_cast<std::uint32_t>(*v);
  if (j.contains("named"))
    if (auto v = c.boolean(j["named"], p + "/named")) r.named = *v;
  if (j.contains("vacant"))
    if (auto v = c.boolean(j["vacant"], p + "/vacant")) r.vacant = *v;
  if (j.contains("zero_read_only"))
    if (auto v = c.boolean(j["zero_read_only"], p + "/zero_read_only")) r.zero_read_only = *v;
  if (j.contains("locals")) {
    const auto& l = j["locals"];
    if (!l.is_array() || l.size() != 2) {
      c.fail(p + "/locals", "must be [first, last]");
    } else {
      const auto a = c.integer(l[0], p + "/locals/0", 1, 1000000);
      const auto b = c.integer(l[1], p + "/locals/1", 1, 1000000);
      if (a && b) {
        if (*b < *a) c.fail(p + "/locals", "last before first");
        r.local_first = static_cast<std::uint32_t>(*a);
        r.local_last = static_cast<std::uint32_t>(*b);
      }
    }
  }
  if (j.contains("ranges")) {
    const auto& rs = j["ranges"];
    if (!rs.is_array()) {
      c.fail(p + "/ranges", "must be an array");
    } else {
      for (std::size_t i = 0; i < rs.size(); ++i) {
        const std::string q = p + "/ranges/" + std::to_string(i);
        if (!c.object(rs[i], q, {"first", "last", "source", "name", "assumed", "writable"},
                      {"first", "last", "source", "name"}))
          continue;
        ParameterRange range;
        const auto a = c.integer(rs[i]["first"], q + "/first", 0, 1000000);
        const auto b = c.integer(rs[i]["last"], q + "/last", 0, 1000000);
        const auto s = c.choice(rs[i]["source"], q + "/source", kSources);
        const auto n = c.string(rs[i]["name"], q + "/name");
        if (!a || !b || !s || !n) continue;
        if (*b < *a) c.fail(q, "last before first");
        range.first = static_cast<std::uint32_t>(*a);
        range.last = static_cast<std::uint32_t>(*b);
        range.source = *s;
        range.name = *n;
        if (rs[i].contains("assumed"))
          if (auto v = c.number(rs[i]["assumed"], q + "/assumed", -1e12, 1e12)) range.assumed = *v;
        if (rs[i].contains("writable"))
          if (auto v = c.boolean(rs[i]["writable"], q + "/writable")) range.writable = *v;
        r.ranges.push_back(std::move(range));
      }
    }
  }
  if (j.contains("assign_in_order"))
    if (auto v = c.boolean(j["assign_in_order"], p + "/assign_in_order")) r.assign_in_order = *v;
  if (j.contains("alarm"))
    if (auto v = c.integer(j["alarm"], p + "/alarm", 1, 1000000))
      r.alarm = static_cast<std::uint32_t>(*v);
  if (j.contains("stop_message"))
    if (auto v = c.integer(j["stop_message"], p + "/stop_message", 1, 1000000))
      r.stop_message = static_cast<std::uint32_t>(*v);
  if (j.contains("machine_names")) {
    const auto& m = j["machine_names"];
    if (!m.is_array()) {
      c.fail(p + "/machine_names", "must be an array");
    } else {
      for (std::size_t i = 0; i < m.size(); ++i)
        if (auto v = c.string(m[i], p + "/machine_names/" + std::to_string(i))) {
          std::string up = *v;
          for (char& ch : up) ch = detail::upper(ch);
          r.machine_name_prefixes.push_back(up);
        }
    }
  }
}

void read_expressions(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/expressions";
  if (!c.object(j, p, {"brackets", "operators", "functions", "atan_slash", "address_equals"},
                {"brackets", "operators", "functions"}))
    return;
  auto& e = d.expressions;
  if (j.contains("brackets"))
    if (auto v = c.choice<int>(j["brackets"], p + "/brackets", {{"[]", 0}, {"()", 1}})) {
      e.open = *v == 0 ? '[' : '(';
      e.close = *v == 0 ? ']' : ')';
    }
  if (j.contains("operators")) {
    const auto& ops = j["operators"];
    if (!ops.is_array()) {
      c.fail(p + "/operators", "must be an array");
    } else {
      for (std::size_t i = 0; i < ops.size(); ++i) {
        const std::string q = p + "/operators/" + std::to_string(i);
        if (!c.object(ops[i], q, {"spelling", "op", "precedence"},
                      {"spelling", "op", "precedence"}))
          continue;
        const auto s = c.string(ops[i]["spelling"], q + "/spelling");
        const auto o = c.choice(ops[i]["op"], q + "/op", kOperators);
        const auto pr = c.integer(ops[i]["precedence"], q + "/precedence", 1, 50);
        if (s && (s->empty() || s->size() > 8)) c.fail(q + "/spelling", "1 to 8 characters");
        if (s && o && pr && !s->empty()) e.operators.push_back({*s, *o, static_cast<int>(*pr)});
      }
      // Longest spelling first: "**" before "*", "<=" before "<".
      std::stable_sort(e.operators.begin(), e.operators.end(), [](const auto& a, const auto& b) {
        return a.spelling.size() > b.spelling.size();
      });
    }
  }
  if (j.contains("functions")) {
    const auto& fs = j["functions"];
    if (!fs.is_object()) {
      c.fail(p + "/functions", "must be an object");
    } else {
      for (const auto& [name, value] : fs.items()) {
        if (name.empty() ||
            (!valid_word_name(name) &&
             !(name.size() <= 8 && std::all_of(name.begin(), name.end(), [](char ch) {
                 return (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
               })))) {
          c.fail(p + "/functions/" + name, "a function name is upper-case letters and digits");
          continue;
        }
        if (auto f = c.choice(value, p + "/functions/" + name, kFunctions))
          e.functions.push_back({name, *f});
      }
    }
  }
  if (j.contains("atan_slash"))
    if (auto v = c.boolean(j["atan_slash"], p + "/atan_slash")) e.atan_slash = *v;
  if (j.contains("address_equals"))
    if (auto v = c.boolean(j["address_equals"], p + "/address_equals")) e.address_equals = *v;
}

void read_flow(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/flow";
  if (!c.object(j, p,
                {"o_words", "fanuc_subprograms", "macro_b", "sinumerik", "packed_repeat", "while"},
                {}))
    return;
  auto& f = d.flow;
  for (const auto& [key, field] :
       std::vector<std::pair<const char*, bool*>>{{"o_words", &f.o_words},
                                                  {"fanuc_subprograms", &f.fanuc_subprograms},
                                                  {"macro_b", &f.macro_b},
                                                  {"sinumerik", &f.sinumerik},
                                                  {"packed_repeat", &f.packed_repeat}}) {
    if (j.contains(key))
      if (auto v = c.boolean(j[key], p + "/" + key)) *field = *v;
  }
  if (j.contains("while")) {
    const auto& w = j["while"];
    if (!w.is_array()) {
      c.fail(p + "/while", "must be an array");
    } else {
      for (std::size_t i = 0; i < w.size(); ++i)
        if (auto v = c.string(w[i], p + "/while/" + std::to_string(i))) {
          if (!valid_word_name(*v)) c.fail(p + "/while/" + std::to_string(i), "upper-case letters");
          f.while_spellings.push_back(*v);
        }
      std::sort(f.while_spellings.begin(), f.while_spellings.end(),
                [](const auto& a, const auto& b) { return a.size() > b.size(); });
    }
  }
}

// One entry of /codes or /keywords.
std::optional<CodeSpec> read_code_spec(Checker& c, const Dialect& d, const json& value,
                                       const std::string& q, const std::string& key) {
  if (!c.object(value, q,
                {"group", "action", "index", "index_word", "cycle", "requires", "requires_one_of",
                 "allows", "refusal", "warn", "planes"},
                {"action"}))
    return std::nullopt;
  CodeSpec spec;
  spec.text = key;
  if (auto a = c.choice(value["action"], q + "/action", action_names())) spec.action = *a;
  if (value.contains("group")) {
    if (auto g = c.string(value["group"], q + "/group")) {
      const auto it = std::find(d.modal_groups.begin(), d.modal_groups.end(), *g);
      if (it == d.modal_groups.end())
        c.fail(q + "/group", "'" + *g + "' is not in /modal_groups");
      else
        spec.group = static_cast<int>(it - d.modal_groups.begin());
    }
  }
  if (value.contains("index"))
    if (auto v = c.integer(value["index"], q + "/index", 0, 57)) spec.index = static_cast<int>(*v);
  if (value.contains("index_word")) {
    const auto n = c.string(value["index_word"], q + "/index_word");
    const WordId w = n ? d.word(*n) : kNoWord;
    if (n && (w == kNoWord || (n->size() == 1 && !d.letter_known[w])))
      c.fail(q + "/index_word", "'" + *n + "' is not a word of this dialect");
    else
      spec.index_word = w;
  }
  if (value.contains("cycle")) {
    const auto& cy = value["cycle"];
    if (c.object(cy, q + "/cycle", {"kind", "feed_out_to_clear"}, {"kind"})) {
      if (auto k = c.choice(cy["kind"], q + "/cycle/kind", kCycleKinds)) spec.cycle.kind = *k;
      if (cy.contains("feed_out_to_clear"))
        if (auto v = c.boolean(cy["feed_out_to_clear"], q + "/cycle/feed_out_to_clear"))
          spec.cycle.feed_out_to_clear = *v;
    }
  } else if (spec.action == Action::Cycle) {
    c.fail(q + "/cycle", "a cycle code needs its cycle kind");
  }
  if (value.contains("requires"))
    spec.requires_all = word_list(c, d, value["requires"], q + "/requires");
  if (value.contains("requires_one_of"))
    spec.requires_one_of = word_list(c, d, value["requires_one_of"], q + "/requires_one_of");
  if (value.contains("allows")) spec.allows = word_list(c, d, value["allows"], q + "/allows");
  if (value.contains("refusal"))
    if (auto v = c.string(value["refusal"], q + "/refusal")) spec.refusal = *v;
  if (value.contains("warn"))
    if (auto v = c.boolean(value["warn"], q + "/warn")) spec.warn = *v;
  if (value.contains("planes")) {
    const auto& planes = value["planes"];
    if (!planes.is_array() || planes.empty()) {
      c.fail(q + "/planes", "must be a non-empty array of xy, xz, yz");
    } else {
      spec.planes = 0;
      for (std::size_t i = 0; i < planes.size(); ++i)
        if (auto b = c.choice<std::uint8_t>(planes[i], q + "/planes/" + std::to_string(i),
                                            {{"xy", 1}, {"xz", 2}, {"yz", 4}}))
          spec.planes = static_cast<std::uint8_t>(spec.planes | *b);
    }
  }
  return spec;
}

void read_codes(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/codes";
  if (!j.is_object()) {
    c.fail(p, "must be an object");
    return;
  }
  d.g_index.assign(10000, -1);
  d.m_index.assign(10000, -1);
  for (const auto& [key, value] : j.items()) {
    const std::string q = p + "/" + key;
    bool m = false;
    int number = 0;
    if (!parse_code_key(key, m, number)) {
      c.fail(q, "a code is G or M with up to four digits (G: and one decimal)");
      continue;
    }
    auto spec = read_code_spec(c, d, value, q, key);
    if (!spec) continue;
    auto& index = m ? d.m_index : d.g_index;
    if (index[static_cast<std::size_t>(number)] >= 0) {
      c.fail(q, "the same code twice");
      continue;
    }
    index[static_cast<std::size_t>(number)] = static_cast<std::int16_t>(d.codes.size());
    d.codes.push_back(std::move(*spec));
  }
  // The tables end at the highest code: lookups beyond are "unknown" without memory.
  auto shrink = [](std::vector<std::int16_t>& v) {
    std::size_t n = v.size();
    while (n > 0 && v[n - 1] < 0) --n;
    v.resize(n);
  };
  shrink(d.g_index);
  shrink(d.m_index);
}

// Codes spelled as words: Sinumerik CIP, BSPLINE, SUPA, TRANS, DIAMON, ...
void read_keywords(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/keywords";
  if (!j.is_object()) {
    c.fail(p, "must be an object");
    return;
  }
  for (const auto& [key, value] : j.items()) {
    const std::string q = p + "/" + key;
    if (key.size() < 2 || key.size() > 16 ||
        !std::all_of(key.begin(), key.end(),
                     [](char ch) {
                       return (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
                     }) ||
        key[0] < 'A' || key[0] > 'Z') {
      c.fail(q, "a keyword is 2 to 16 upper-case letters, digits and underscores, a letter first");
      continue;
    }
    auto spec = read_code_spec(c, d, value, q, key);
    if (!spec) continue;
    d.keywords.emplace_back(key, static_cast<std::int16_t>(d.codes.size()));
    d.codes.push_back(std::move(*spec));
  }
  std::stable_sort(d.keywords.begin(), d.keywords.end(),
                   [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
}

WordId named_word(Checker& c, const Dialect& d, const json& j, const std::string& path) {
  const auto s = c.string(j, path);
  if (!s) return kNoWord;
  const WordId w = d.word(*s);
  if (w == kNoWord || (s->size() == 1 && !d.letter_known[w])) {
    c.fail(path, "'" + *s + "' is not a word of this dialect");
    return kNoWord;
  }
  return w;
}

void read_arcs(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/arcs";
  if (!c.object(j, p,
                {"radius_word", "turns_word", "turns", "centres", "tolerance_mm", "tolerance_inch",
                 "relative", "absolute_factor"},
                {"centres"}))
    return;
  auto& a = d.arcs;
  if (j.contains("radius_word")) a.radius = named_word(c, d, j["radius_word"], p + "/radius_word");
  if (j.contains("turns_word")) a.turns = named_word(c, d, j["turns_word"], p + "/turns_word");
  if (j.contains("turns"))
    if (auto v = c.choice<bool>(j["turns"], p + "/turns", {{"total", false}, {"extra", true}}))
      a.turns_extra = *v;
  if (j.contains("centres"))
    if (auto v = c.choice<bool>(j["centres"], p + "/centres",
                                {{"incremental", false}, {"absolute", true}}))
      a.centre_absolute = *v;
  if (j.contains("tolerance_mm"))
    if (auto v = c.number(j["tolerance_mm"], p + "/tolerance_mm", 0, 100)) a.tolerance_mm = *v;
  if (j.contains("tolerance_inch"))
    if (auto v = c.number(j["tolerance_inch"], p + "/tolerance_inch", 0, 4)) a.tolerance_inch = *v;
  if (j.contains("relative"))
    if (auto v = c.number(j["relative"], p + "/relative", 0, 1)) a.relative = *v;
  if (j.contains("absolute_factor"))
    if (auto v = c.number(j["absolute_factor"], p + "/absolute_factor", 1, 1e6))
      a.absolute_factor = *v;
}

void read_cycles(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/cycles";
  if (!c.object(j, p,
                {"r_word", "peck_word", "dwell_word", "repeat_word", "dwell_scale",
                 "peck_clearance", "chip_break_retract", "clearance_is_machine"},
                {}))
    return;
  auto& cy = d.cycles;
  // Without G8x cycles (Sinumerik calls CYCLE81..) the words may be left out.
  cy.r_plane = cy.peck = cy.dwell = kNoWord;
  if (j.contains("r_word")) cy.r_plane = named_word(c, d, j["r_word"], p + "/r_word");
  if (j.contains("peck_word")) cy.peck = named_word(c, d, j["peck_word"], p + "/peck_word");
  if (j.contains("dwell_word")) cy.dwell = named_word(c, d, j["dwell_word"], p + "/dwell_word");
  cy.repeat = kNoWord;
  if (j.contains("repeat_word")) cy.repeat = named_word(c, d, j["repeat_word"], p + "/repeat_word");
  if (j.contains("dwell_scale"))
    if (auto v = c.number(j["dwell_scale"], p + "/dwell_scale", 0, 1000, true)) cy.dwell_scale = *v;
  auto pair = [&](const char* key, double& mm, double& inch) {
    if (!j.contains(key)) return;
    const std::string q = p + "/" + key;
    if (!c.object(j[key], q, {"mm", "inch"}, {"mm", "inch"})) return;
    if (auto v = c.number(j[key]["mm"], q + "/mm", 0, 100)) mm = *v;
    if (auto v = c.number(j[key]["inch"], q + "/inch", 0, 4)) inch = *v;
  };
  pair("peck_clearance", cy.peck_clearance_mm, cy.peck_clearance_inch);
  pair("chip_break_retract", cy.chip_break_mm, cy.chip_break_inch);
  if (j.contains("clearance_is_machine"))
    if (auto v = c.boolean(j["clearance_is_machine"], p + "/clearance_is_machine"))
      cy.clearance_is_machine = *v;
}

void read_dwell(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/dwell";
  if (!j.is_object() || j.empty()) {
    c.fail(p, "must be an object of word → seconds per unit");
    return;
  }
  for (const auto& [name, value] : j.items()) {
    const WordId w = d.word(name);
    if (w == kNoWord || (name.size() == 1 && !d.letter_known[w])) {
      c.fail(p + "/" + name, "'" + name + "' is not a word of this dialect");
      continue;
    }
    // A number (seconds per unit), or {"scale": .., "integer_scale": ..}.
    if (value.is_object()) {
      const std::string q = p + "/" + name;
      if (!c.object(value, q, {"scale", "integer_scale"}, {"scale"})) continue;
      const auto s = c.number(value["scale"], q + "/scale", 0, 1000, true);
      double integer = 0;
      if (value.contains("integer_scale"))
        if (auto v = c.number(value["integer_scale"], q + "/integer_scale", 0, 1000, true))
          integer = *v;
      if (s) d.dwell.words.push_back({w, *s, integer});
    } else if (auto v = c.number(value, p + "/" + name, 0, 1000, true)) {
      d.dwell.words.push_back({w, *v, 0});
    }
  }
}

void read_program(Checker& c, const json& j, Dialect& d) {
  const std::string p = "/program";
  if (!c.object(j, p, {"initial_motion", "initial_retract", "end_required", "assumed_tool_length"},
                {"end_required"}))
    return;
  if (j.contains("initial_motion")) {
    if (auto s = c.string(j["initial_motion"], p + "/initial_motion")) {
      bool m = false;
      int number = 0;
      const CodeSpec* spec = nullptr;
      if (parse_code_key(*s, m, number) && !m) spec = d.g_code(number);
      if (!spec || !(spec->action == Action::Rapid || spec->action == Action::Linear ||
                     spec->action == Action::CycleCancel))
        c.fail(p + "/initial_motion",
               "must be a G code of this dialect for rapid, linear or cycle_cancel");
      else
        d.initial_motion =
            spec->action == Action::CycleCancel ? -1 : static_cast<int>(spec - d.codes.data());
    }
  }
  if (j.contains("initial_retract"))
    if (auto v = c.choice<bool>(j["initial_retract"], p + "/initial_retract",
                                {{"initial", false}, {"r", true}}))
      d.initial_retract_r = *v;
  if (j.contains("end_required"))
    if (auto v = c.choice<int>(j["end_required"], p + "/end_required",
                               {{"error", 2}, {"warning", 1}, {"no", 0}})) {
      d.require_program_end = *v > 0;
      d.missing_end_is_error = *v == 2;
    }
  if (j.contains("assumed_tool_length"))
    if (auto v = c.number(j["assumed_tool_length"], p + "/assumed_tool_length", 0, 10000, true))
      d.assumed_tool_length = *v;
}

}  // namespace

DialectResult load_dialect(std::string_view json_text) {
  DialectResult result;
  json j;
  try {
    j = json::parse(json_text.begin(), json_text.end());
  } catch (const json::parse_error& e) {
    result.diagnostics.push_back(
        diag::json_syntax_error(diag::Code::GcodeDialectJson, json_text, e, "not valid JSON: "));
    return result;
  }
  Checker c(result.diagnostics);
  auto d = std::make_shared<Dialect>();
  if (!c.object(j, "",
                {"$schema", "id", "name", "syntax", "units", "lexical", "numbers", "words",
                 "parameters", "expressions", "flow", "modal_groups", "codes", "keywords", "arcs",
                 "cycles", "dwell", "program"},
                {"id", "name", "syntax", "units", "lexical", "words", "parameters", "expressions",
                 "flow", "modal_groups", "codes", "arcs", "cycles", "dwell", "program"}))
    return result;
  if (auto id = c.string(j["id"], "/id")) {
    d->id = *id;
    const bool ok = !id->empty() && id->size() <= 64 &&
                    std::all_of(id->begin(), id->end(),
                                [](char ch) {
                                  return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                                         ch == '.' || ch == '_' || ch == '-';
                                }) &&
                    (std::isalnum(static_cast<unsigned char>((*id)[0])) != 0);
    if (!ok) c.fail("/id", "a profile id: [a-z0-9][a-z0-9._-]*, at most 64 characters");
  }
  if (auto name = c.string(j["name"], "/name")) d->name = *name;
  if (auto s =
          c.choice<Syntax>(j["syntax"], "/syntax",
                           {{"word_address", Syntax::WordAddress}, {"klartext", Syntax::Klartext}}))
    d->syntax = *s;
  if (auto u = c.choice<bool>(j["units"], "/units", {{"mm", true}, {"inch", false}}))
    d->metric = *u;
  read_lexical(c, j["lexical"], *d);
  if (j.contains("numbers")) {
    const auto& n = j["numbers"];
    if (c.object(n, "/numbers", {"integers_are_increments", "increment_mm", "increment_inch"},
                 {"integers_are_increments"})) {
      if (n.contains("integers_are_increments"))
        if (auto v = c.boolean(n["integers_are_increments"], "/numbers/integers_are_increments"))
          d->integer_literal_increments = *v;
      if (n.contains("increment_mm"))
        if (auto v = c.number(n["increment_mm"], "/numbers/increment_mm", 0, 1, true))
          d->increment_mm = *v;
      if (n.contains("increment_inch"))
        if (auto v = c.number(n["increment_inch"], "/numbers/increment_inch", 0, 1, true))
          d->increment_inch = *v;
    }
  }
  read_words(c, j["words"], *d);
  read_parameters(c, j["parameters"], *d);
  read_expressions(c, j["expressions"], *d);
  read_flow(c, j["flow"], *d);
  if (!j["modal_groups"].is_array()) {
    c.fail("/modal_groups", "must be an array of names");
  } else {
    for (std::size_t i = 0; i < j["modal_groups"].size(); ++i)
      if (auto g = c.string(j["modal_groups"][i], "/modal_groups/" + std::to_string(i))) {
        if (std::find(d->modal_groups.begin(), d->modal_groups.end(), *g) != d->modal_groups.end())
          c.fail("/modal_groups/" + std::to_string(i), "a group named twice");
        d->modal_groups.push_back(*g);
      }
    if (d->modal_groups.size() > 64) c.fail("/modal_groups", "at most 64 groups");
  }
  if (c.ok()) read_codes(c, j["codes"], *d);
  if (c.ok() && j.contains("keywords")) read_keywords(c, j["keywords"], *d);
  if (c.ok()) {
    read_arcs(c, j["arcs"], *d);
    read_cycles(c, j["cycles"], *d);
    read_dwell(c, j["dwell"], *d);
    read_program(c, j["program"], *d);
  }
  if (d->parameters.style == ParameterStyle::Hash && d->parameters.count == 0)
    c.fail("/parameters/count", "required with style hash");
  if (d->syntax == Syntax::WordAddress && d->expressions.operators.empty())
    c.fail("/expressions/operators", "at least one operator");
  if (!c.ok()) return result;
  result.dialect = std::move(d);
  return result;
}

}  // namespace ncpost::gcode
