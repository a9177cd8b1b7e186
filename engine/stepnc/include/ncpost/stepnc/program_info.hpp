#pragma once
// Program-information extraction: what a STEP-NC controller shows before it runs a program.
//
// In:  a Model (read from P21 or P28) and the EXPRESS schema that describes it: every attribute
//      is read by name through the schema (attributes.hpp), and "executable" means a subtype of
//      ISO 14649-10 EXECUTABLE in that schema.
// Out: a ProgramInfo: the header, the PROJECT → main WORKPLAN → executables tree, the
//      workpieces and tools, instance counts by entity type, and diagnostics about the program
//      structure. Its JSON form, which `ncpost inspect` and the HTTP service share, is made at
//      the edge (pipeline/jobs.hpp) and described in docs/inspect.md.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace ncpost::stepnc {

// A header field: a string, a list of strings, or unset (absent or `$`).
using HeaderValue = std::variant<std::monostate, std::string, std::vector<std::string>>;

struct Header {
  // FILE_DESCRIPTION's and FILE_NAME's fields by their ISO 10303-21 names, in file order:
  // description, implementation_level, name, time_stamp, author, organization,
  // preprocessor_version, originating_system, authorization.
  std::vector<std::pair<std::string, HeaderValue>> fields;
  std::vector<std::string> schemas;  // FILE_SCHEMA
};

// An instance as a program shows it: id, entity and its its_id (unset when it has none).
struct EntityRef {
  std::uint64_t id = 0;
  std::string type;
  std::optional<std::string> name;
};

// One executable of the workplan tree. Which members mean something depends on `shape`.
struct Executable {
  enum class Shape : std::uint8_t {
    Leaf,         // NC functions, RAPID_MOVEMENT, an element of an unknown type, ...
    Workingstep,  // feature, operation, tool
    Sequence,     // WORKPLAN, NON_SEQUENTIAL, SELECTIVE: `children` are the elements
    Parallel,     // PARALLEL: `children` are the branches
    If,           // IF_STATEMENT: children[0] the true branch, children[1] the false one
    While,        // WHILE_STATEMENT: children[0] the body
    Message,      // DISPLAY_MESSAGE: `text`
    ToolChange,   // LOAD_TOOL, UNLOAD_TOOL: `tool`
  };
  EntityRef self;
  Shape shape = Shape::Leaf;
  std::optional<EntityRef> feature, operation, tool;
  std::optional<EntityRef> setup;  // a Sequence's set-up, where the reader names it (AP238)
  std::optional<std::string> text;
  std::vector<Executable> children;
  // An If branch or a While body that the file leaves unset: only `missing` is meaningful.
  bool missing = false;
};

struct Project {
  std::uint64_t id = 0;
  std::string name;
  std::optional<Executable> main_workplan;  // unset when it is not a WORKPLAN
};

struct Workpiece {
  EntityRef self;
  std::optional<std::string> material;  // its material's identifier
  std::optional<std::size_t> clamping_positions;
};

struct ToolUse {
  EntityRef self;
  std::vector<std::uint64_t> used_by;  // workingsteps and tool changes, in program order
  // What an AP238 AIM file gives beyond the ARM's summary (engine/ap238), when it gives it:
  // the number the tool is loaded as, its body, and its dimensions in mm.
  std::optional<int> number;
  std::optional<std::string> body;
  std::optional<double> diameter, corner_radius, length;
};

struct Statistics {
  std::size_t bytes = 0;
  std::size_t instances = 0;
  std::size_t workingsteps = 0;
  // Instances per entity type; a complex instance counts as "(A+B+...)".
  std::map<std::string, std::size_t> by_type;
};

struct ProgramInfo {
  Header header;
  std::optional<Project> project;  // unset when the file has no PROJECT
  std::vector<Workpiece> workpieces;
  std::vector<ToolUse> tools;
  Statistics statistics;
  std::vector<diag::Diagnostic> diagnostics;  // about the program structure
};

// Receives the workplan tree as inspect walks it, so that a large program's tree need not be
// held (`ncpost inspect` writes it as it comes). Each executable arrives without its children
// (`enter`), then its children do, then `leave`; an If branch or a While body the file leaves
// unset arrives as an Executable with `missing` set.
class TreeVisitor {
 public:
  virtual ~TreeVisitor() = default;
  // The project, its main_workplan unset, before the executables of its main workplan.
  virtual void begin_project(const Project& project) = 0;
  virtual void enter(const Executable& executable) = 0;
  virtual void leave(const Executable& executable) = 0;
  virtual void end_project() = 0;
};

// The events of a tree already built, in the order inspect would give them.
void replay(const Executable& root, TreeVisitor& visitor);

struct InspectOptions {
  // Workplans nested deeper than this are reported instead of followed.
  unsigned max_nesting = 64;
  // How entities are read (variants.hpp): the job's mode.
  Mode mode = Mode::Tolerant;
  // When set, the workplan tree goes to the visitor, and the ProgramInfo's main workplan is
  // its root alone (without children).
  TreeVisitor* visitor = nullptr;
};

// With the schema given: no check that it is the model's.
[[nodiscard]] ProgramInfo inspect(const p21::Model& model, const express::SchemaSet& schema,
                                  const InspectOptions& options = {});
// With the schema the registry selects for the model's FILE_SCHEMA; when it has none, the
// built-in ISO 14649 schema, and the diagnostics say so (EXP-050 warning, EXP-052 note).
[[nodiscard]] ProgramInfo inspect(const p21::Model& model, const express::SchemaRegistry& schemas,
                                  const InspectOptions& options = {});

// The header (FILE_DESCRIPTION, FILE_NAME, FILE_SCHEMA) and the instance counts of any model,
// whatever its schema: the AP238 AIM inspector shares them.
[[nodiscard]] Header read_header(const p21::Model& model);
[[nodiscard]] Statistics count_instances(const p21::Model& model, std::size_t workingsteps);

// Why a model without a PROJECT is not an ISO 14649 program: an AP238 AIM file (STEPNC-006:
// engine/ap238 reads those), or no program at all (STEPNC-001). Shared by inspect and the
// interpreter.
[[nodiscard]] diag::Diagnostic no_program_diagnostic(const p21::Model& model);

// A human-readable tree of the same information (`ncpost inspect --format text`).
[[nodiscard]] std::string format_text(const ProgramInfo& info);

// format_text's text, written to `out` as inspect walks the model (InspectOptions::visitor):
// the header first, each executable as it arrives, the rest at finish(). The tree is never
// held, so a large program's text costs no more memory than its JSON.
class TextWriter final : public TreeVisitor {
 public:
  using Sink = std::function<void(std::string_view)>;
  TextWriter(const Header& header, Sink out);
  void begin_project(const Project& project) override;
  void enter(const Executable& executable) override;
  void leave(const Executable& executable) override;
  void end_project() override {}
  // What follows the tree (or "project: none" when there was none): workpieces, tools, counts.
  void finish(const ProgramInfo& info);

 private:
  struct Open {
    Executable::Shape shape;
    std::size_t children = 0;
  };
  Sink out_;
  std::vector<Open> open_;
  bool saw_project_ = false;
};

}  // namespace ncpost::stepnc
