// libFuzzer target for the ISO 10303-21 reader: any input must give a model and diagnostics,
// never a crash, a hang or a sanitizer report. Read in pieces by p21::StreamReader, and read in
// pieces side by side (ReadOptions::helpers, pieces of 16 bytes or more, the helper's pieces run
// first), it must give the same diagnostics and model. After a clean read, writing the model and
// reading it again must succeed with an equal model (the writer's contract). A clean model is
// then checked against the schema in both modes a job reads it in (strict, and tolerant with
// the variants table's schema names and entity aliases), which must not crash either.

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/express/registry.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/stream_reader.hpp"
#include "ncpost/p21/writer.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace {

// Pieces of pseudo-random sizes (1..64 bytes) that depend on the input only.
ncpost::p21::ReadResult read_in_pieces(std::string_view text) {
  ncpost::p21::StreamReader reader(text.size());
  std::uint32_t state = static_cast<std::uint32_t>(text.size()) * 2654435761u + 1;
  std::size_t at = 0;
  while (at < text.size()) {
    state = state * 1664525u + 1013904223u;
    const std::size_t take = std::min<std::size_t>(1 + (state >> 26), text.size() - at);
    (void)reader.append(text.substr(at, take));
    at += take;
    reader.read_more(reader.appended());
  }
  return reader.finish();
}

// Side by side: every piece a helper is offered runs at once, before the reader's own piece,
// which is the order most likely to expose state shared between the pieces.
ncpost::p21::ReadResult read_side_by_side(std::string text) {
  static const ncpost::parallel::Helpers at_once{[](const ncpost::parallel::Task& task) { task(); },
                                                 3};
  ncpost::p21::ReadOptions options;
  options.helpers = &at_once;
  options.min_piece_bytes = 16;
  return ncpost::p21::read(std::move(text), options);
}

bool same_diagnostics(const ncpost::p21::ReadResult& a, const ncpost::p21::ReadResult& b) {
  if (a.diagnostics.size() != b.diagnostics.size()) return false;
  for (std::size_t i = 0; i < a.diagnostics.size(); ++i) {
    const auto& x = a.diagnostics[i];
    const auto& y = b.diagnostics[i];
    if (x.code != y.code || x.line != y.line || x.column != y.column || x.message != y.message)
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  const auto streamed = read_in_pieces(text);
  const auto side_by_side = read_side_by_side(text);
  const auto first = ncpost::p21::read(std::move(text));
  for (const auto* other : {&streamed, &side_by_side})
    if (!same_diagnostics(first, *other) ||
        ncpost::p21::first_difference(first.model, other->model))
      __builtin_trap();
  // Decode every string: decoding must cope with whatever the reader let through.
  std::size_t total = 0;
  for (ncpost::p21::Value v : first.model.all_values())
    if (v.kind() == ncpost::p21::ValueKind::String) total += first.model.as_string(v).size();
  if (!first.ok()) return 0;
  const auto second = ncpost::p21::read(ncpost::p21::write_to_string(first.model));
  if (!second.ok() || ncpost::p21::first_difference(first.model, second.model)) __builtin_trap();
  static const ncpost::express::SchemaRegistry registry;
  for (const auto mode : {ncpost::stepnc::Mode::Strict, ncpost::stepnc::Mode::Tolerant}) {
    const auto selection =
        registry.select_or_builtin(first.model, ncpost::stepnc::schema_aliases(mode));
    ncpost::express::ValidateOptions options;
    options.tolerant = mode == ncpost::stepnc::Mode::Tolerant;
    options.entity_aliases = ncpost::stepnc::entity_aliases(mode);
    total += ncpost::express::validate(first.model, *selection.set(), options).size();
  }
  return static_cast<int>(total & 0);
}
