#pragma once
// The JSON form of the canonical trace, for programs that draw or analyse a toolpath (the
// browser front end): the same calls, numbers and line numbers as the text trace (trace.hpp),
// each call one JSON object with named members instead of positional arguments. docs/canon.md,
// "The JSON trace", lists the members of every call.
//
// Two layouts of the same records:
// - Lines (NDJSON, application/x-ndjson): a header object on the first line, one call per
//   line, then an end record {"end": true, ...}, so that a reader can act on each line as it
//   arrives and knows that it has all of them;
// - Document (application/json): {header members..., "calls": [one call per line], end
//   members...}.
// The header is {"format": "ncpost-trace", "version": 1} plus whatever members the caller
// adds (the pipeline adds the workpieces' stock boxes); the end members are the caller's too
// (the pipeline gives ok, calls and diagnostics).

#include <cstdint>
#include <string>
#include <string_view>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {

enum class JsonLayout : std::uint8_t { Lines, Document };

// {"n": line, "call": "NAME", members...} without a newline. `line` is the text trace's line
// number of the call.
void append_json_call(std::string& out, const Call& call, std::uint64_t line);
// A JSON string: \" \\ \b \f \n \r \t, \u00XX for other control characters, U+FFFD for bytes
// that are not valid UTF-8 (JSON text is Unicode; the text trace's \xHH has no JSON form).
void append_json_string(std::string& out, std::string_view text);
// A number as the text trace prints it (4 decimals); null when it is not finite.
void append_json_number(std::string& out, double value);

class JsonTraceWriter final : public Sink {
 public:
  // `header_members`: extra members of the header, as JSON text without braces (e.g.
  // `"stock": [...]`), or empty.
  JsonTraceWriter(TextSink out, JsonLayout layout, std::string header_members = {});

  void call(const Call& call) override;
  // Writes the header if no call did, then the end record (Lines) or closes the calls and the
  // document with `end_members` (JSON text without braces, may be empty). Once.
  void finish(std::string_view end_members = {});

 private:
  void header();
  TextSink out_;
  JsonLayout layout_;
  std::string header_members_;
  std::string line_;
  std::uint64_t next_line_ = 1;
  bool header_written_ = false;
  bool finished_ = false;
};

}  // namespace ncpost::canon
