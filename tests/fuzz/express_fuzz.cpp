// libFuzzer target for the EXPRESS (ISO 10303-11) schema parser (engine/express): any source
// must give a SchemaSet and diagnostics, never a crash, a hang or a sanitizer report. The
// SchemaSet is usable even with errors, so every parse is also written as EXPRESS-X (which walks
// every declaration, reference and flattened attribute), and a parse is deterministic: the same
// source parsed again gives the same diagnostics. The limits are the defaults a server upload
// meets, except a smaller input cap so that one input stays fast.

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/express/express_x.hpp"
#include "ncpost/express/parse.hpp"

namespace {

std::string text_of(const ncpost::express::ParseResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics) out += ncpost::diag::format(d, "f") + "\n";
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view source(reinterpret_cast<const char*>(data), size);
  ncpost::express::ParseLimits limits;
  limits.max_input_bytes = std::size_t{1} << 20;
  const auto first = ncpost::express::parse_express(source, limits);
  (void)ncpost::express::to_express_x(first.schemas);
  const auto again = ncpost::express::parse_express(source, limits);
  if (text_of(first) != text_of(again)) __builtin_trap();
  // At most max_errors errors, plus the one that says parsing stopped (EXP-013).
  std::size_t errors = 0;
  for (const auto& d : first.diagnostics)
    if (d.severity == ncpost::diag::Severity::Error) ++errors;
  if (errors > limits.max_errors + 1) __builtin_trap();
  return 0;
}
