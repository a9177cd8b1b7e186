#pragma once
// The render engine's XSLT 1.0 part (libxslt + EXSLT). In: a profile stylesheet (compiled once,
// then shared read-only by every worker thread) and one XML document per job or chunk (the
// canonical program's XML form, docs/canon.md). Out: the serialized result (as xsl:output
// says) and diagnostics pointing at the stylesheet's file:line. Nothing is printed.
//
// Security, limits and error capture: docs/xslt.md. Extension functions (urn:ncpost:ext):
// docs/xslt-extensions.md.
//
//   ncpost::xslt::initialise();                                   // main thread, at start-up
//   auto compiled = compile(dir / "post.xsl", {{dir, common}});   // once per profile
//   JobState job(config);                                         // once per job (program)
//   for (each chunk) transform(*compiled.stylesheet, chunk_xml, job);

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/xslt/input_tree.hpp"

namespace ncpost::xslt {

// Process-wide set-up, once, on the main thread, before any other thread uses libxml2 or
// libxslt: installs libxml2's counting allocator (for the memory limit), initialises the
// parser, libxslt and EXSLT, the security defaults, the import loader, the error channel and
// the urn:ncpost:ext module. Later calls do nothing. compile() and transform() refuse to run
// (XSLT-007) until it has been called.
void initialise();
[[nodiscard]] bool initialised() noexcept;

// Every limit of the stage (docs/xslt.md lists them with their reasons). Zero means
// "no limit" only where noted.
struct Limits {
  // Compile time.
  std::size_t max_stylesheet_bytes = std::size_t{4} << 20;  // per stylesheet file
  std::size_t max_stylesheet_files = 64;                    // main + imports + includes
  // Transform time (each call of transform()).
  // Nested templates and instructions (libxslt's ctxt->depth). Each level is C stack: 1000 fits
  // 8 MiB thread stacks with room to spare, also under AddressSanitizer (libxslt's own is 3000).
  int max_template_depth = 1000;
  int max_template_vars = 15000;         // live variables and parameters
  std::uint64_t max_steps = 10'000'000;  // XSLT instructions executed (0: none; about 2 s)
  std::uint64_t max_xpath_ops =
      100'000'000;  // XPath operations, libxml2 opLimit (0: none; about 1 s)
  std::size_t max_memory = std::size_t{512}
                           << 20;  // live bytes allocated by libxml2/libxslt (0: none)
  std::chrono::milliseconds max_time{
      10'000};  // wall clock, checked as memory is allocated (0: none)
  std::size_t max_input_bytes = std::size_t{1} << 30;  // the XML text given to transform()
  std::size_t max_diagnostics = 100;  // per compile or transform; then one XSLT-026
};

// Compile and run-time errors name the stylesheet (or an imported one); input errors name the
// input.
using diag::FileDiagnostic;

// A compiled stylesheet. Immutable after compile(); share it with std::shared_ptr<const ...>
// between threads. Each transform gets its own transform context.
class CompiledStylesheet {
 public:
  CompiledStylesheet(const CompiledStylesheet&) = delete;
  CompiledStylesheet& operator=(const CompiledStylesheet&) = delete;
  ~CompiledStylesheet();

  // The file the stylesheet was compiled from (or named as, for compile_text()).
  [[nodiscard]] const std::filesystem::path& file() const noexcept { return file_; }
  // Every file it was read from, the main one first, then imports and includes (canonical
  // paths): what a cache must watch.
  [[nodiscard]] const std::vector<std::filesystem::path>& files() const noexcept { return files_; }
  // xsl:output method: "xml" (also when absent), "text" or "html".
  [[nodiscard]] const std::string& output_method() const noexcept { return method_; }

 private:
  friend struct Access;
  CompiledStylesheet(void* style, std::filesystem::path file,
                     std::vector<std::filesystem::path> files, std::string method);
  void* style_;  // xsltStylesheetPtr; kept opaque so users need no libxslt headers
  std::filesystem::path file_;
  std::vector<std::filesystem::path> files_;  // every file it was read from (main first)
  std::string method_;
};

struct CompileResult {
  std::shared_ptr<const CompiledStylesheet> stylesheet;  // null when there are errors
  std::vector<FileDiagnostic> diagnostics;               // warnings too, when it compiled
  [[nodiscard]] bool ok() const noexcept { return stylesheet != nullptr; }
};

// Compiles a stylesheet file. xsl:import and xsl:include resolve (after symbolic links and
// `..`) only to files under one of `allowed_roots` (the profile's folder and the shared
// stylesheets/common/ folder); URLs and anything else are refused (XSLT-004). The main file
// must lie under a root as well. Roots that do not exist are ignored.
[[nodiscard]] CompileResult compile(const std::filesystem::path& file,
                                    std::span<const std::filesystem::path> allowed_roots,
                                    const Limits& limits = {});
// The same for stylesheet text that is not (yet) on disk, e.g. an uploaded profile. `as_file`
// names it in diagnostics and is the base for relative imports; it need not exist.
[[nodiscard]] CompileResult compile_text(std::string_view text,
                                         const std::filesystem::path& as_file,
                                         std::span<const std::filesystem::path> allowed_roots,
                                         const Limits& limits = {});

// ---- Configuration of the extension functions (filled from a profile's profile.json) ----

enum class Units : std::uint8_t { Millimetre, Inch };

// How ext:format writes one quantity. The value is first scaled (inch conversion for lengths
// and feeds, then `scale`), rounded to `decimals` as printf rounds the exact binary value, then:
//   trailing_zeros = false: "1.500" -> "1.5", "10.000" -> "10."
//   decimal_point  = false: "10."   -> "10"  (a forced point is FANUC's "10.")
//   leading_zero   = false: "0.5"   -> ".5", "-0.5" -> "-.5"
struct NumberFormat {
  int decimals = 3;  // 0..12
  bool decimal_point = true;
  bool leading_zero = true;
  bool trailing_zeros = false;
  double scale = 1.0;  // extra factor, e.g. 1000 for a dwell in milliseconds
};

// ext:block(): start, start + increment, ...; a number beyond `maximum` wraps to `start`.
// `numbered`: whether blocks carry N numbers at all (ext:block-line, ext:block-numbering).
struct BlockNumbers {
  std::int64_t start = 10;
  std::int64_t increment = 10;
  std::int64_t maximum = 99999;
  bool numbered = false;
};

// The machine set-up transform of ext:setup-x/y/z: p' = M p + t, M row-major. A rotation is
// best built with from_rotation() (docs/xslt-extensions.md explains the convention).
struct SetupTransform {
  std::array<double, 9> matrix{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 3> translation{0, 0, 0};

  // The machine axes turned by `angle_degrees` (right-hand rule) about `axis` relative to the
  // program axes, then shifted by `translation` (in machine axes). As in the XSLT paper:
  // 90 degrees about Z maps program (x, y, z) to machine (y, -x, z).
  [[nodiscard]] static SetupTransform from_rotation(std::array<double, 3> axis,
                                                    double angle_degrees,
                                                    std::array<double, 3> translation = {0, 0, 0});
};

// ext:comment(): which characters survive, upper-casing, and what replaces the others.
// Parentheses and control characters are always replaced, so a comment cannot close early.
struct CommentRules {
  std::string allowed =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 .,-+*/=:#%_";
  bool upper_case = false;
  std::string replacement = " ";  // for each refused character (may be empty: dropped)
  std::size_t max_length = 0;     // 0: no limit; longer comments are cut
};

struct JobConfig {
  Units units = Units::Millimetre;  // the controller's units (ext:units())
  NumberFormat length{3, true, true, false, 1.0};
  NumberFormat angle{3, true, true, false, 1.0};
  NumberFormat feed{1, true, true, false, 1.0};
  NumberFormat speed{0, false, true, false, 1.0};
  NumberFormat dwell{3, true, true, false, 1.0};
  BlockNumbers block;
  SetupTransform setup;
  CommentRules comment;
  std::size_t max_line_length = 0;  // ext:line(): 0 means no limit
  std::size_t max_modal_groups = 256;
  // The rotary addresses A, B, C that ext:motion-words() and ext:motion-run() write when a
  // motion carries rotary axes: a five-axis profile's two (profile.json kinematics), all
  // three otherwise.
  std::array<bool, 3> rotary_axes{true, true, true};
};

// A motion that ext:motion-run() renders from memory. A renderer may write one
// `<motions first="F" count="N"/>` element for N consecutive motions instead of N elements,
// and hand their values to the job (JobState::set_run_motions) before the transform; the
// values are the ones the elements would carry (docs/render.md, "Motion runs").
struct RunMotion {
  enum class Kind : std::uint8_t { Traverse, Feed, Arc };
  enum class Plane : std::uint8_t { Xy, Yz, Xz };
  Kind kind = Kind::Feed;
  double x = 0, y = 0, z = 0;  // end point
  bool has_rotary = false;
  double a = 0, b = 0, c = 0;  // rotary axes, when has_rotary
  // Arcs: centre, plane, and turns signed about the plane's normal (never 0).
  double cx = 0, cy = 0, cz = 0;
  Plane plane = Plane::Xy;
  int rotation = 1;
};

// The state of one job (one program, rendered in one or many transforms, one thread at a
// time): block counter, modal memory, program units, last C angle, current position. Create one per
// job; do not share it between concurrent transforms.
class JobState {
 public:
  explicit JobState(JobConfig config = {}, Limits limits = {});

  [[nodiscard]] const JobConfig& config() const noexcept { return config_; }
  [[nodiscard]] const Limits& limits() const noexcept { return limits_; }
  // Back to the start of a program (block numbers, modal memory, units, C angle, position).
  void reset();

  // The motions that the next transform's <motions> elements refer to by index; the span must
  // stay valid until the transform returns. Each is marked when ext:motion-run renders it.
  void set_run_motions(std::span<const RunMotion> motions);
  // How many of them were not rendered (a stylesheet without a template for <motions>).
  [[nodiscard]] std::size_t run_motions_not_rendered() const noexcept;

  // The job's cancel flag (null: never cancelled). A transform polls it as it works, so a
  // stylesheet that loops gives its thread back when the job is cancelled, not only when a
  // limit stops it; it then ends with TransformResult::cancelled and no error.
  void set_cancel(const std::atomic<bool>* cancel) noexcept { cancel_ = cancel; }
  [[nodiscard]] const std::atomic<bool>* cancel() const noexcept { return cancel_; }

 private:
  friend struct Access;
  JobConfig config_;
  Limits limits_;
  const std::atomic<bool>* cancel_ = nullptr;
  std::int64_t next_block_;
  std::map<std::string, std::string, std::less<>> modal_;
  double program_unit_mm_ = 1.0;  // ext:program-units(): the canonical program's length unit
  double last_c_ = 0.0;           // ext:rotary(): C kept when the tool axis is vertical
  std::array<double, 3> position_{0, 0, 0};  // ext:moved-to() / ext:position()
  bool has_position_ = false;
  std::span<const RunMotion> run_motions_;
  std::vector<std::uint8_t> run_rendered_;  // per motion of run_motions_: rendered yet
};

// Top-level xsl:param values, passed as strings (quoted, never evaluated as XPath).
using Params = std::vector<std::pair<std::string, std::string>>;

struct TransformResult {
  std::string output;  // serialized as the stylesheet's xsl:output says; empty on error
  std::vector<FileDiagnostic> diagnostics;
  bool ok = false;         // no error diagnostic and the transform finished normally
  bool cancelled = false;  // stopped by the JobState's cancel flag: not ok, no error added
};

// Parses `xml` (no DTD, no entity expansion, no network; XSLT-006/010) and applies the
// stylesheet with a fresh transform context, the job's limits and security preferences, and
// the job's extension state. `input_name` names the document in diagnostics. Errors end the
// job, never the process; the next call works as before.
[[nodiscard]] TransformResult transform(const CompiledStylesheet& stylesheet, std::string_view xml,
                                        JobState& job, const Params& params = {},
                                        std::string_view input_name = "input.xml");
// The same for a document built in memory (input_tree.hpp): no parse. The tree is read, never
// changed, and can be cleared and reused after the call.
[[nodiscard]] TransformResult transform(const CompiledStylesheet& stylesheet, const InputTree& tree,
                                        JobState& job, const Params& params = {},
                                        std::string_view input_name = "input.xml");

}  // namespace ncpost::xslt
