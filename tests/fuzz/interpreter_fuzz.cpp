// libFuzzer target for the interpreter on top of the reader: any model the reader accepts must
// give a canonical program or diagnostics, never a crash, a hang or a sanitizer report. The
// model is interpreted whether or not it validates against the schema: the interpreter must
// cope with whatever a hostile file holds. The schema check runs in both modes first: tolerant
// (the default) must never report an error that strict (`--strict`) does not. Then the model is
// interpreted in both modes (stepnc::Mode), each with the schema and aliases a job of that mode
// uses.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace {

class NullSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call&) override { ++calls; }
  std::size_t calls = 0;
};

std::size_t errors(const std::vector<ncpost::diag::Diagnostic>& diagnostics) {
  return static_cast<std::size_t>(
      std::count_if(diagnostics.begin(), diagnostics.end(),
                    [](const auto& d) { return d.severity == ncpost::diag::Severity::Error; }));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ncpost::express::SchemaRegistry registry;
  auto read = ncpost::p21::read(std::string(reinterpret_cast<const char*>(data), size));
  if (!read.ok()) return 0;
  const auto selection = registry.select_or_builtin(read.model);
  // No limit: a strict check that stopped at it would have counted fewer errors.
  ncpost::express::ValidateOptions strict;
  strict.max_diagnostics = std::numeric_limits<std::size_t>::max();
  ncpost::express::ValidateOptions tolerant = strict;
  tolerant.tolerant = true;
  if (errors(ncpost::express::validate(read.model, *selection.set(), tolerant)) >
      errors(ncpost::express::validate(read.model, *selection.set(), strict)))
    std::abort();
  // Then the job's two readings: strict as written, tolerant through the variants table (its
  // schema names choose the schema, its entity aliases are checked as what they stand for), the
  // implicit values and the units cross-check. Neither may crash.
  std::size_t calls = 0;
  for (const auto mode : {ncpost::stepnc::Mode::Strict, ncpost::stepnc::Mode::Tolerant}) {
    const auto chosen =
        registry.select_or_builtin(read.model, ncpost::stepnc::schema_aliases(mode));
    ncpost::express::ValidateOptions options =
        mode == ncpost::stepnc::Mode::Strict ? strict : tolerant;
    options.entity_aliases = ncpost::stepnc::entity_aliases(mode);
    calls += ncpost::express::validate(read.model, *chosen.set(), options).size();
    const ncpost::stepnc::AttributeReader attributes(read.model, *chosen.set(), mode);
    NullSink sink;
    const auto result = ncpost::stepnc::interpret(read.model, attributes, sink);
    calls += result.calls + sink.calls;
  }
  return static_cast<int>(calls & 0);
}
