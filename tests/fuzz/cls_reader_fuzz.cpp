// libFuzzer target for the CL reader (engine/cls): any input must give canonical calls and
// diagnostics, never a crash, a hang or a sanitizer report. Read in pieces (pseudo-random sizes
// that depend on the input) it must give the same calls and diagnostics as read whole; the
// shop's checks (the example section of tests/golden/cls/checks.json, built in here) run on
// every input; every call must trace; the Begin/End markers must pair up when the read ends
// normally; and format detection must not crash.

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/canon/trace.hpp"
#include "ncpost/cls/checks.hpp"
#include "ncpost/cls/reader.hpp"

namespace {

const ncpost::cls::CheckConfig& checks() {
  static const ncpost::cls::CheckConfig config = [] {
    std::vector<ncpost::diag::Diagnostic> d;
    auto c = ncpost::cls::parse_checks(std::string_view(R"({
      "tool_names": {"unmatched": "warning", "patterns": [
        {"regex": "^T[0-9]+-D(?P<diameter>[0-9.]+)(?:-CR(?P<corner_radius>[0-9.]+))?$"},
        {"regex": "^BALL-(?P<diameter>[0-9.]+)$", "ball": true}]},
      "heads": {"types": {"straight": [1], "head30": [0.8660254], "head90": [0]},
                "default": "straight"},
      "operation_rules": [{"match": "_H30$", "head": "head30"},
                          {"match": "_SUB", "options": {"subprogram": "on"}}]})"),
                                       d);
    if (!c) __builtin_trap();
    return std::move(*c);
  }();
  return config;
}

// Counts the structure markers on their way to the trace.
class Markers final : public ncpost::canon::Sink {
 public:
  explicit Markers(ncpost::canon::Sink& next) : next_(next) {}
  void call(const ncpost::canon::Call& c) override {
    if (std::holds_alternative<ncpost::canon::Begin>(c)) ++open;
    if (std::holds_alternative<ncpost::canon::End>(c)) --open;
    if (std::holds_alternative<ncpost::canon::ProgramEnd>(c)) ++program_ends;
    next_.call(c);
  }
  long open = 0;
  int program_ends = 0;

 private:
  ncpost::canon::Sink& next_;
};

std::string text_of(const ncpost::cls::ReadResult& r, const std::string& trace) {
  std::string out = trace;
  for (const auto& d : r.diagnostics) out += ncpost::diag::format(d, "f") + "\n";
  for (const auto& [k, v] : r.selected_options) out += k + "=" + v + "\n";
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ncpost::cls::ReadOptions options;
  options.checks = &checks();
  options.max_record_bytes = 4096;

  std::string whole_trace;
  ncpost::canon::TraceWriter whole_writer([&](std::string_view s) { whole_trace += s; });
  Markers whole_markers(whole_writer);
  const auto whole = ncpost::cls::read(text, whole_markers, options);

  std::string piece_trace;
  ncpost::canon::TraceWriter piece_writer([&](std::string_view s) { piece_trace += s; });
  ncpost::cls::Reader reader(piece_writer, options);
  std::uint32_t state = static_cast<std::uint32_t>(size) * 2654435761u + 1;
  for (std::size_t at = 0; at < size;) {
    state = state * 1664525u + 1013904223u;
    const std::size_t take = std::min<std::size_t>(1 + (state >> 26), size - at);
    reader.feed(text.substr(at, take));
    at += take;
  }
  const auto pieces = reader.finish();
  if (text_of(whole, whole_trace) != text_of(pieces, piece_trace)) __builtin_trap();

  // A read that ran to its end closes what it opened and ends with one PROGRAM_END.
  if (!ncpost::diag::has_errors(whole.diagnostics) && !whole.cancelled &&
      (whole_markers.open != 0 || whole_markers.program_ends != 1))
    __builtin_trap();
  (void)ncpost::cls::looks_like_cl(text.substr(0, 4096));
  return 0;
}
