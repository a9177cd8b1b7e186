#pragma once
// The path verifier: does a canonical program machine the features its workingsteps claim?
//
// In:  a Model and its AttributeReader (the program is interpreted here, through the same
//      interpreter as `ncpost trace`, so whatever produced the motions — explicit toolpaths or a
//      feature toolpath generator — is what gets checked), and options (tolerance, grid, tools).
// Out: a VerifyResult: the interpreter's diagnostics, one Finding per failed check (workingstep,
//      feature, position, motion index), and one FeatureReport per feature that a workingstep
//      machined (depth and floor coverage). Nothing is printed; format_text / format_json render.
//
// Independence: the feature boundaries, the swept tool and the stock model are computed here
// with their own, simple geometry (distance to a profile of lines and arcs, a raster of the
// floor, a height field of the stock). Nothing is shared with the toolpath generator
// (engine/stepnc/src/features), so a bug there shows up here. docs/verify.md has the algorithms,
// tolerances and limits.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::verify {

struct VerifyOptions {
  stepnc::InterpretOptions interpret{};
  // mm. How far a motion may cross a boundary (wall, floor), miss a depth, or stand off a hole
  // axis before it is a failure; also the margin of the stock model.
  double tolerance = 0.01;
  // mm. Cell size of the floor raster for the coverage check. Unset: the smallest tool radius
  // used on the feature / 20, kept within [0.05, 1].
  std::optional<double> grid{};
  // A raster never has more cells than this; the grid is coarsened until it fits (and the report
  // says so). Bounds memory (1 byte + 1 float per cell) whatever the feature size.
  std::size_t max_cells = 4'000'000;
  // mm. Cell size of the stock height field used for the rapid and plunge checks.
  double stock_grid = 0.5;
};

struct Position {
  double x = 0;
  double y = 0;
  double z = 0;
};

// One failed check (or a note about what could not be checked).
struct Finding {
  diag::Diagnostic diagnostic;    // code, severity, line:column of the workingstep, message
  std::uint64_t workingstep = 0;  // P21 id; 0: outside any workingstep
  std::string workingstep_name;
  std::uint64_t feature = 0;  // P21 id; 0: none
  std::optional<Position> position{};
  std::size_t motion = 0;      // 1-based index among the program's motions; 0: none
  std::size_t trace_line = 0;  // the call's line in `ncpost trace`; 0: none
};

struct FeatureReport {
  std::uint64_t id = 0;
  std::string type;  // entity, e.g. "CLOSED_POCKET"
  std::string name;
  bool checked = false;
  std::string not_checked_reason;
  std::size_t workingsteps = 0;
  // Machine coordinates (z) of the floor and of the depth the program must reach (floor plus the
  // smallest bottom allowance of its operations; for a through feature, the floor).
  double floor_z = 0;
  double target_z = 0;
  bool through = false;
  std::optional<Position> deepest{};  // lowest feed position of the tool tip
  bool depth_reached = false;
  // Coverage of the floor at target_z.
  bool coverage_checked = false;
  double grid = 0;
  double tool_radius = 0;         // smallest tool radius used on the feature
  double reachable_area = 0;      // mm², the floor a tool of that radius can reach
  double unreachable_area = 0;    // mm², floor in corners narrower than the tool
  double uncovered_fraction = 0;  // of the reachable area
  std::optional<Position> uncovered_sample{};
};

struct VerifyResult {
  std::vector<diag::Diagnostic> interpreter;  // the interpreter's own diagnostics
  std::vector<Finding> findings;
  std::vector<FeatureReport> features;
  double tolerance = 0;
  std::size_t calls = 0;
  std::size_t motions = 0;
  std::size_t workingsteps = 0;
  std::size_t rapids_below_secplane_in_air = 0;  // below the security plane over the part, clear
  // options.interpret.cancel was set before the verification ended (the interpreter polls it
  // before each executable, the coverage before each feature): the findings may be
  // incomplete, so they are no verdict; the reports say "cancelled".
  bool cancelled = false;
  [[nodiscard]] bool ok() const;  // not cancelled, and no error among interpreter and findings
};

[[nodiscard]] VerifyResult verify(const p21::Model& model,
                                  const stepnc::AttributeReader& attributes,
                                  const VerifyOptions& options = {});

// The same checks on a canonical program produced elsewhere (the calls of `interpret` into a
// canon::ProgramBuffer, a generator's output, a test's hand-made calls). `interpreter` is empty.
[[nodiscard]] VerifyResult verify_calls(const p21::Model& model,
                                        const stepnc::AttributeReader& attributes,
                                        std::span<const canon::Call> calls,
                                        const VerifyOptions& options = {});

// The stock as a viewer draws it: each workpiece whose its_bounding_geometry is a BLOCK, with
// the block's eight corners in machine coordinates, placed as the checks place it (the setup's
// its_origin, then the workpiece set-up's). A workpiece is listed once per SETUP that holds it
// (`setup` its id); a program without a SETUP lists every workpiece in its own coordinates
// (`setup` 0). Workpieces without a BLOCK are left out.
struct StockBox {
  std::uint64_t workpiece = 0;  // P21 id
  std::string name;
  std::uint64_t setup = 0;  // P21 id; 0: none
  // Corner k is the block's origin plus x if k & 1, y if k & 2, z if k & 4.
  std::vector<Position> corners;
};
[[nodiscard]] std::vector<StockBox> stock_boxes(const p21::Model& model,
                                                const stepnc::AttributeReader& attributes);

// The report: one line per feature, the rapids summary, the result. Diagnostics are not in it
// (the CLI prints them to stderr as `file:line:column: severity: CODE: message`).
[[nodiscard]] std::string format_text(const VerifyResult& result, std::string_view file);
// Everything, diagnostics included, as one JSON document.
[[nodiscard]] std::string format_json(const VerifyResult& result, std::string_view file);

}  // namespace ncpost::verify
