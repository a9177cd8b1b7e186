// libFuzzer target for G-code in (engine/gcode): any bytes, read with every built-in dialect
// (stylesheets/*/dialect.json) into canonical calls and into the XML form, must give a program
// and diagnostics — never a crash, a hang or a sanitizer report. The input is also its own
// subprogram file (calls by name or number find it again: recursion must stay bounded), and is
// tried as a dialect.json text and through format detection. Limits are lowered so one input
// stays fast; the limits themselves are unit-tested in tests/unit/gcode.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "ncpost/canon/sink.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace {

class NullSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call&) override { ++calls; }
  std::size_t calls = 0;
};

std::vector<std::shared_ptr<const ncpost::gcode::Dialect>> built_in_dialects() {
  std::vector<std::shared_ptr<const ncpost::gcode::Dialect>> out;
  for (const auto& e : std::filesystem::directory_iterator(NCPOST_STYLESHEETS_DIR)) {
    const auto file = e.path() / "dialect.json";
    if (!std::filesystem::exists(file)) continue;
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    auto loaded = ncpost::gcode::load_dialect(text.str());
    if (loaded.dialect) out.push_back(std::move(loaded.dialect));
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto dialects = built_in_dialects();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::size_t sum = ncpost::gcode::looks_like_gcode(text.substr(0, 4096)) ? 1 : 0;
  sum += ncpost::gcode::load_dialect(text).diagnostics.size();
  ncpost::gcode::ReadOptions options;
  options.program_name = "fuzz";
  options.max_steps = 20'000;
  options.max_errors = 50;
  options.max_call_depth = 16;
  options.subprograms.push_back({"O1", std::string(text)});
  options.subprograms.push_back({"SUB", std::string(text)});
  for (const auto& dialect : dialects) {
    NullSink sink;
    const auto r = ncpost::gcode::read(text, *dialect, sink, options);
    std::size_t bytes = 0;
    const auto x = ncpost::gcode::write_xml(
        text, *dialect, [&](std::string_view piece) { bytes += piece.size(); }, options);
    sum += r.calls + sink.calls + x.calls + bytes;
  }
  return static_cast<int>(sum & 0);
}
