#pragma once
// The text trace: one call per line, in the style of the NIST interpreters and LinuxCNC
// `rs274`, so that outputs can be diffed against them. In: calls. Out: lines such as
//     16 STRAIGHT_FEED(91.9000, -13.5000, 2.5000)
// (`%5d` line number from 1, a space, the call). rs274's " N..... " is left out. The format
// of every call is in docs/canon.md.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"

namespace ncpost::canon {

using TextSink = std::function<void(std::string_view)>;

// "NAME(args)" without line number or newline.
[[nodiscard]] std::string format_call(const Call& call);
void append_call(std::string& out, const Call& call);

// A number as the trace prints it: fixed, 4 decimals, rounded as printf("%.4f") rounds, in
// the C locale; anything that rounds to zero prints 0.0000 (never -0.0000).
void append_number(std::string& out, double value);
// A string as the trace prints it: in double quotes, with \" \\ \n \r \t, and \xHH for other
// control characters and for bytes that are not valid UTF-8. Valid UTF-8 passes unchanged.
void append_quoted(std::string& out, std::string_view text);

// Prints each call as one numbered line to `out`, as it arrives. Numbering continues across
// calls to call() and write(), so a program traced chunk by chunk equals the whole trace.
class TraceWriter final : public Sink {
 public:
  explicit TraceWriter(TextSink out, std::uint64_t first_line = 1)
      : out_(std::move(out)), next_line_(first_line) {}

  void call(const Call& call) override;
  void write(std::span<const Call> calls);

  [[nodiscard]] std::uint64_t next_line() const noexcept { return next_line_; }

 private:
  TextSink out_;
  std::uint64_t next_line_;
  std::string line_;
};

// The whole trace of `calls`, lines numbered from 1.
[[nodiscard]] std::string trace(std::span<const Call> calls);

}  // namespace ncpost::canon
