#pragma once
// The ISO 14649 interpreter: Model → canonical machining program.
//
// In:  a Model, an AttributeReader over its schema, and options (tool table, limits).
// Out: canonical calls on `sink`, structure markers included, so a canon::Chunker downstream
//      can hand each workingstep on as soon as it is complete; and the diagnostics. Anything the
//      interpreter does not implement is named (STEPNC-010 with the #id and entity), never
//      dropped in silence.
//
// What it executes: PROJECT → main WORKPLAN → executables in order (docs/interpreter.md):
// nested WORKPLANs, MACHINING_WORKINGSTEPs and RAPID_MOVEMENTs with explicit toolpaths (POLYLINE,
// TRIMMED_CURVE of LINE, CIRCLE or HELIX, COMPOSITE_CURVE, B_SPLINE_CURVE_WITH_KNOTS, rational
// or not), NC functions, and NON_SEQUENTIAL / PARALLEL / SELECTIVE / IF / WHILE with the
// behaviour docs/interpreter.md states.

#include <atomic>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/sink.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/features.hpp"

namespace ncpost::stepnc {

// A tool table in NIST's format (POCKET FMS TLO DIAM HOLDER DESCRIPTION): which pocket holds the
// tool whose its_id is FMS, and its length offset.
struct ToolTableEntry {
  int pocket = 0;
  std::string name;
  double length_offset = 0;
  double diameter = 0;
};
struct ToolTable {
  std::vector<ToolTableEntry> entries;
  [[nodiscard]] const ToolTableEntry* find(std::string_view name) const;
};
[[nodiscard]] ToolTable read_tool_table(std::string_view text,
                                        std::vector<diag::Diagnostic>& diagnostics);

struct InterpretOptions {
  // Without a table, a tool's pocket is its P21 id and its length offset its
  // overall_assembly_length (0 when unset).
  std::optional<ToolTable> tools;
  // Workplans nested deeper than this are reported, not followed.
  unsigned max_nesting = 64;
  // How far (mm) an arc's end points may lie off its circle before it is an error.
  double arc_tolerance = 0.001;
  // Stop at the first executable after an error, without the program's end sequence: what is
  // posted to a machine must not look complete when it is not. `ncpost trace` goes on, to show
  // everything it can.
  bool stop_at_first_error = false;
  // Checked before each executable: a cancelled job (its client went away, or it ran out of
  // time) stops there, without the program's end sequence. Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
  // Toolpath generation for workingsteps without explicit toolpaths (docs/features.md).
  FeatureOptions features{};
  // The AP238 AIM interpreter (engine/ap238) stops after this many errors (AP238-011), so that
  // a hostile file cannot make it report without end. The ISO 14649 interpreter reports at most
  // a few errors per instance and does not count them.
  std::size_t max_errors = 1000;
};

struct InterpretResult {
  std::vector<diag::Diagnostic> diagnostics;
  std::size_t calls = 0;
  [[nodiscard]] bool ok() const;
};

[[nodiscard]] InterpretResult interpret(const p21::Model& model, const AttributeReader& attributes,
                                        canon::Sink& sink, const InterpretOptions& options = {});

}  // namespace ncpost::stepnc
