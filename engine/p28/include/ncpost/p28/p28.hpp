#pragma once
// ISO 10303-28 (P28): the XML forms of a P21 model, in both directions.
//
// Two bindings (docs/p28.md shows both on the same instance):
//  - Late: every instance is an `entity_instance` element whose attributes are
//    `attribute_instance` / `inherited_attribute_instance` elements holding typed literals, as in
//    the XSLT post-processor paper. Generic: stylesheets can walk any schema the same way.
//  - Early: the ISO 10303-28 edition 2 default configuration. One element per entity, named
//    after it, attributes as named child elements, references as `ref` attributes, inside the
//    `iso_10303_28` / `uos` envelope.
//
// The schema gives names and types. Without one (or for an entity it lacks) attributes are
// written by position, which still reads back to the same model.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"

namespace ncpost::p28 {

enum class Binding : std::uint8_t { Late, Early };

// Streams the model as P28 to `sink`, in pieces of bounded size: no DOM, memory beyond the
// model is constant. `schemas` may be null. Returns notes about what had no schema.
[[nodiscard]] std::vector<diag::Diagnostic> write(const p21::Model& model,
                                                  const express::SchemaSet* schemas,
                                                  Binding binding, const p21::TextSink& sink);

struct ReadOptions {
  // Chooses the schema from the document's header once it has been read (FILE_SCHEMA), when
  // `read` is given no schema. Called at most once, before the first data section.
  std::function<const express::SchemaSet*(const p21::Model& header_only)> schema_for_header;
  // Element nesting deeper than this is rejected (libxml2's own limit, 256, also applies).
  std::uint32_t max_depth = 128;
  // Documents larger than this are rejected before parsing.
  std::size_t max_bytes = std::size_t{1} << 31;
  std::size_t max_errors = 1000;
  // Set by another thread to stop reading (a client that went away, a job out of time): looked
  // at every 4096 XML nodes. The result is then `cancelled`, with no model and no diagnostics.
  // Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

// Reads a P28 document of either binding (recognised from its elements) into a Model. Untrusted
// input is safe: no DTD is accepted (so no entity can expand), nothing is loaded from files or
// the network, and depth and size are limited; each violation is one diagnostic.
[[nodiscard]] p21::ReadResult read(std::string_view xml, const express::SchemaSet* schemas,
                                   const ReadOptions& options = {});

// Process-wide set-up for libxml2; call once on the main thread before any worker uses P28
// (the CLI and the server do). It also installs an entity loader that refuses every file and URL.
void initialise_xml();

}  // namespace ncpost::p28
