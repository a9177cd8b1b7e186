// libFuzzer target for the AP238 AIM path on top of the reader: any model the reader accepts
// is interpreted and inspected by engine/ap238 with the built-in AP238 AIM schema (whatever
// its FILE_SCHEMA says, so that every input reaches the AIM code), whether or not it validates:
// a canonical program or diagnostics, never a crash, a hang or a sanitizer report. The vendor
// JSON (Next-NC's circular motions), unit chains and the backward links are all input-driven.

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/ap238/ap238.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"

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
  const ncpost::express::SchemaSet& schema = registry.builtin_aim().set();
  const ncpost::stepnc::AttributeReader attributes(read.model, schema);
  NullSink sink;
  ncpost::stepnc::InterpretOptions options;
  options.max_errors = 50;
  const auto result = ncpost::ap238::interpret(read.model, attributes, sink, options);
  const auto info = ncpost::ap238::inspect(read.model, schema);
  return static_cast<int>((result.calls + sink.calls + info.diagnostics.size()) & 0);
}
