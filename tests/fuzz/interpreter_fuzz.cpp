// libFuzzer target for the interpreter on top of the reader: any model the reader accepts must
// give a canonical program or diagnostics, never a crash, a hang or a sanitizer report. The
// model is interpreted whether or not it validates against the schema: the interpreter must
// cope with whatever a hostile file holds.

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace {

class NullSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call&) override { ++calls; }
  std::size_t calls = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ncpost::express::SchemaRegistry registry;
  auto read = ncpost::p21::read(std::string(reinterpret_cast<const char*>(data), size));
  if (!read.ok()) return 0;
  const auto selection = registry.select_or_builtin(read.model);
  const ncpost::stepnc::AttributeReader attributes(read.model, *selection.set());
  NullSink sink;
  const auto result = ncpost::stepnc::interpret(read.model, attributes, sink);
  return static_cast<int>((result.calls + sink.calls) & 0);
}
