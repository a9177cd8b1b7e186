// libFuzzer target for the ISO 10303-21 reader: any input must give a model and diagnostics,
// never a crash, a hang or a sanitizer report. After a clean read, writing the model and
// reading it again must succeed with an equal model (the writer's contract).

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  const auto first = ncpost::p21::read(std::move(text));
  // Decode every string: decoding must cope with whatever the reader let through.
  std::size_t total = 0;
  for (ncpost::p21::Value v : first.model.all_values())
    if (v.kind() == ncpost::p21::ValueKind::String) total += first.model.as_string(v).size();
  if (!first.ok()) return 0;
  const auto second = ncpost::p21::read(ncpost::p21::write_to_string(first.model));
  if (!second.ok() || ncpost::p21::first_difference(first.model, second.model)) __builtin_trap();
  return static_cast<int>(total & 0);
}
