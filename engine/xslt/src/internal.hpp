#pragma once
// Internals of the XSLT stage shared by its source files: private access to the public
// classes, the per-call error collector, the memory/time budget, and the process-wide pieces
// that initialise() installs (runtime.cpp).

#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <libxslt/security.h>
#include <libxslt/xsltInternals.h>

#include <atomic>
#include <chrono>
#include <cstdarg>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/xslt/input_tree.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::xslt {

// The friend of CompiledStylesheet and JobState.
struct Access {
  static xsltStylesheetPtr style(const CompiledStylesheet& s) noexcept {
    return static_cast<xsltStylesheetPtr>(s.style_);
  }
  static std::shared_ptr<const CompiledStylesheet> make(xsltStylesheetPtr style,
                                                        std::filesystem::path file,
                                                        std::vector<std::filesystem::path> files,
                                                        std::string method) {
    return std::shared_ptr<const CompiledStylesheet>(
        new CompiledStylesheet(style, std::move(file), std::move(files), std::move(method)));
  }
  static std::int64_t& next_block(JobState& j) noexcept { return j.next_block_; }
  static auto& modal(JobState& j) noexcept { return j.modal_; }
  static double& program_unit_mm(JobState& j) noexcept { return j.program_unit_mm_; }
  static double& last_c(JobState& j) noexcept { return j.last_c_; }
  static std::array<double, 3>& position(JobState& j) noexcept { return j.position_; }
  static bool& has_position(JobState& j) noexcept { return j.has_position_; }
  static InputTree::Impl& tree(const InputTree& t) noexcept { return *t.impl_; }
  static std::span<const RunMotion> run_motions(const JobState& j) noexcept {
    return j.run_motions_;
  }
  static std::vector<std::uint8_t>& run_rendered(JobState& j) noexcept { return j.run_rendered_; }
};

namespace detail {

inline constexpr const char* kExtNamespace = "urn:ncpost:ext";

// Options for every document libxml2 parses here: no entity expansion (no NOENT), no DTD
// loading (no DTDLOAD), no huge-document relaxation (no HUGE), no network.
inline constexpr int kParseOptions = XML_PARSE_NONET | XML_PARSE_NOCDATA;

// An InputTree lent to a new document shell for one transform, and taken back (the shell is
// freed, the nodes stay in the tree's arena).
[[nodiscard]] xmlDocPtr lend_tree(const InputTree& tree, const std::string& url);
void take_back_tree(const InputTree& tree, xmlDocPtr doc);

enum class Phase : std::uint8_t { Compile, Transform };

struct Location {
  std::string file;
  std::uint32_t line = 0;
};

// printf into a std::string (for libxml2's and libxslt's printf-style error callbacks).
[[nodiscard]] std::string vformat(const char* fmt, va_list args);

// The location of a stylesheet node (file from its document's URL, line from libxml2).
[[nodiscard]] Location location_of(const xmlNode* node);

// Collects the diagnostics of one compile or one transform. libxslt reports an error as a
// context line ("runtime error: file F line N element E") followed by the message, through
// printf-like callbacks; libxml2 reports structured errors. Both are turned into
// FileDiagnostics here. Bounded: beyond `max` diagnostics one XSLT-026 note is added.
class Collector {
 public:
  Collector(Phase phase, std::size_t max, std::string default_file, std::string input_name = {});

  // libxslt's process-wide generic channel (compile errors; debug dumps during transforms).
  void generic_text(std::string_view text);
  // A transform context's own channel (run-time errors and xsl:message).
  void transform_text(std::string_view text, const xsltTransformContext* ctxt);
  // libxml2's structured errors (parser, XPath).
  void libxml_error(const xmlError& error);

  void add(diag::Code code, std::string file, std::uint32_t line, std::uint32_t column,
           std::string message, std::optional<diag::Severity> severity = std::nullopt);
  // Our own refusal diagnostic was just added: libxslt's follow-up messages about the same
  // refusal ("read rights ... denied", "unable to load") are dropped, lending their stylesheet
  // line to ours when it has none.
  void refusal_reported() noexcept {
    refusal_index_ = items_.empty() ? std::nullopt : std::optional<std::size_t>(items_.size() - 1);
  }
  // The running transform, whose current instruction locates XPath errors that libxslt does
  // not follow with a located message. Null outside the transform.
  void set_transform_context(const xsltTransformContext* ctxt) noexcept { ctxt_ = ctxt; }
  // Ends pending multi-part messages; call before reading the results.
  void finish();

  [[nodiscard]] std::vector<FileDiagnostic>& items() noexcept { return items_; }
  [[nodiscard]] bool has_errors() const noexcept;
  // Text of libxslt's generic channel during a transform (debug dumps), kept for a failure
  // that nothing else explains.
  [[nodiscard]] const std::string& side_text() const noexcept { return side_; }

 private:
  struct Context {
    std::string file;
    std::uint32_t line = 0;
    std::string element;
    bool warning = false;
  };
  void unit(std::string text, bool transform_channel, const xsltTransformContext* ctxt);
  void message(std::string text, bool transform_channel, const xsltTransformContext* ctxt);
  [[nodiscard]] diag::Code classify(std::string_view message) const;
  [[nodiscard]] bool follow_up(diag::Code code, std::string_view message) const;
  void flush_xpath();

  Phase phase_;
  std::size_t max_;
  std::size_t dropped_ = 0;
  std::string default_file_;
  std::string input_name_;
  std::vector<FileDiagnostic> items_;
  std::string generic_partial_;
  std::string transform_partial_;
  std::optional<Context> pending_;
  struct PendingXPath {
    diag::Code code;
    std::string text;
    Location where;  // the instruction running when it was raised (transforms only)
  };
  std::optional<PendingXPath> pending_xpath_;  // XPath error awaiting libxslt's located message
  const xsltTransformContext* ctxt_ = nullptr;
  std::string side_;
  std::optional<std::size_t> refusal_index_;
};

// Installs `collector` as this thread's receiver of libxslt's generic channel and libxml2's
// error callbacks for the lifetime of the scope, and restores the previous ones.
class ErrorScope {
 public:
  explicit ErrorScope(Collector& collector);
  ~ErrorScope();
  ErrorScope(const ErrorScope&) = delete;
  ErrorScope& operator=(const ErrorScope&) = delete;

 private:
  Collector* previous_;
  xmlStructuredErrorFunc previous_structured_;
  void* previous_structured_context_;
  xmlGenericErrorFunc previous_generic_;
  void* previous_generic_context_;
};

// Memory and time accounting of one transform. The allocator that initialise() installs adds
// every libxml2/libxslt allocation made on this thread while a BudgetScope is active; when the
// live total passes `max_bytes` or the deadline passes, it trips: it records why and where
// and makes libxslt stop at its next instruction and XPath at its next operation (by
// exhausting their operation counters, the only stop switch libxslt checks everywhere).
struct Budget {
  std::size_t max_bytes = 0;
  std::chrono::steady_clock::time_point deadline{};
  bool has_deadline = false;
  std::size_t live = 0;
  std::size_t peak = 0;
  unsigned ticks = 0;
  const std::atomic<bool>* cancel = nullptr;  // the job's, polled with the clock
  enum class Trip : std::uint8_t { None, Memory, Time, Cancelled } tripped = Trip::None;
  const xmlNode* where = nullptr;       // the stylesheet instruction running when it tripped
  std::size_t diagnostics_at_trip = 0;  // errors after this index are consequences of the stop
  xsltTransformContextPtr ctxt = nullptr;
};

class BudgetScope {
 public:
  explicit BudgetScope(Budget& budget);
  ~BudgetScope();
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;

 private:
  Budget* previous_;
};

// The security preferences set on every transform context and used as libxslt's defaults
// (compile time): no file or network writes, no directories, no network reads; file reads
// only for imports inside the compile's roots (compile time) or the stylesheet's own file
// (document(''), served from memory).
[[nodiscard]] xsltSecurityPrefsPtr security_prefs() noexcept;

// The compile in progress on this thread, which the import loader consults.
struct CompileScope {
  std::vector<std::filesystem::path> roots;  // canonical, existing
  const Limits* limits = nullptr;
  Collector* collector = nullptr;
  std::vector<std::filesystem::path> files;  // read so far
  // Where each xsl:import / xsl:include of the files read so far points, by the URI libxslt
  // will ask for (and by its path): refusals use it to name the line of the element.
  std::map<std::string, Location, std::less<>> references;
  bool refused = false;  // the loader refused something
  CompileScope* previous = nullptr;
};
void enter_compile(CompileScope& scope) noexcept;
void leave_compile(CompileScope& scope) noexcept;

// Reads and parses one stylesheet file for the compile on this thread (root check, size
// limit, DTD refusal). `dict` is the dictionary to share (libxslt's), or null.
[[nodiscard]] xmlDocPtr load_stylesheet_file(const std::filesystem::path& path, xmlDictPtr dict,
                                             const Location& referrer);
// Parses stylesheet text held in memory under the name `url` (no root check: the caller did it).
[[nodiscard]] xmlDocPtr parse_stylesheet_text(std::string_view text, const std::string& url,
                                              xmlDictPtr dict);
[[nodiscard]] bool inside(const std::filesystem::path& canonical_path,
                          const std::vector<std::filesystem::path>& roots);

// The urn:ncpost:ext module (ext.cpp).
void register_extensions();

// What the extension module finds in ctxt->_private: the job and the transform's collector.
struct TransformRun {
  JobState* job = nullptr;
  Collector* collector = nullptr;
  xsltTransformContextPtr ctxt = nullptr;
};

}  // namespace detail
}  // namespace ncpost::xslt
