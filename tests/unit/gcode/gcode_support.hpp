#pragma once
// Reading small programs in the unit tests: a built-in dialect by profile id, and the trace of
// a program (without its set-up lines) with its diagnostics.

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "corpus.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace ncpost::gcode::test {

inline std::shared_ptr<const Dialect> dialect(const std::string& id) {
  static std::map<std::string, std::shared_ptr<const Dialect>> cache;
  auto& d = cache[id];
  if (!d) {
    auto r = load_dialect(
        ncpost::test::read_file(ncpost::test::source_dir() / "stylesheets" / id / "dialect.json"));
    EXPECT_TRUE(r.dialect) << id << ": " << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
    d = r.dialect;
  }
  return d;
}

struct Read {
  std::vector<canon::Call> calls;
  ReadResult result;
  // The calls as trace lines without numbers, one per line, leaving out the program's frame:
  // PROJECT_BEGIN and the four set-up calls after it, and every structure marker.
  [[nodiscard]] std::string body() const {
    std::string out;
    for (std::size_t i = 0; i < calls.size(); ++i) {
      const auto& c = calls[i];
      if (i < 5 || std::holds_alternative<canon::Begin>(c) || std::holds_alternative<canon::End>(c))
        continue;
      out += canon::format_call(c) + "\n";
    }
    return out;
  }
  [[nodiscard]] std::string motions() const {
    std::string out;
    for (const auto& c : calls)
      if (canon::is_motion(c)) out += canon::format_call(c) + "\n";
    return out;
  }
  // "CODE line:column" of each diagnostic, in order.
  [[nodiscard]] std::string codes() const {
    std::string out;
    for (const auto& d : result.diagnostics)
      out += std::string(d.diagnostic.code_id()) + " " + std::to_string(d.diagnostic.line) + ":" +
             std::to_string(d.diagnostic.column) + "\n";
    return out;
  }
  [[nodiscard]] bool has(diag::Code code) const {
    for (const auto& d : result.diagnostics)
      if (d.diagnostic.code == code) return true;
    return false;
  }
  [[nodiscard]] std::string messages() const {
    std::string out;
    for (const auto& d : result.diagnostics) out += diag::format(d) + "\n";
    return out;
  }
};

inline Read read(const std::string& text, const std::string& id = "linuxcnc",
                 ReadOptions options = {}) {
  Read r;
  canon::ProgramBuffer buffer;
  options.program_name = options.program_name == "program" ? "t.ngc" : options.program_name;
  r.result = gcode::read(text, *dialect(id), buffer, options);
  r.calls = std::move(buffer).take();
  return r;
}

}  // namespace ncpost::gcode::test
