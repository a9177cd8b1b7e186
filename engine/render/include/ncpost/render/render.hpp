#pragma once
// The render stage: canonical calls → (cycle expansion, NURBS linearisation, limit checks) →
// chunks (canon::Chunker) → batches of chunks as one XML <chunk> → the profile's stylesheet
// with one JobState for the whole program → controller text, appended to `out` as each batch
// is rendered (the program's first chunk at once). docs/render.md.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/canon/xml.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/kinematics.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::render {

using TextSink = std::function<void(std::string_view)>;

// Evaluates a rational B-spline (clamped, as canon::NurbsFeed) at parameter u with de Boor's
// algorithm on homogeneous coordinates.
[[nodiscard]] canon::Point nurbs_point(const canon::NurbsFeed& nurbs, double u);
// The most line segments one NURBS becomes (a bound on time and memory whatever the curve).
inline constexpr std::size_t kMaxNurbsPoints = std::size_t{1} << 16;
// STRAIGHT_FEED end points that follow the curve within `tolerance` (chord deviation measured
// at midpoints of each piece, recursively). The last point is the curve's end. Empty when the
// NURBS is not valid (canon::valid), when its geometry is so large that distances overflow
// (control points near 1e308, weights near 0), or when it needs more than kMaxNurbsPoints.
[[nodiscard]] std::vector<canon::Point> linearize(const canon::NurbsFeed& nurbs, double tolerance);

struct RenderOptions {
  canon::ChunkLimits chunk{};
  // Render the whole program as one chunk (one transform) instead of chunk by chunk: for tests
  // that check chunked output is byte-identical; memory then grows with the program.
  bool single_chunk = false;
  // Batching (docs/render.md): consecutive chunks go through one transform, as one <chunk>,
  // until their XML reaches `batch_bytes`; checked after each chunk, so a batch holds at most
  // one chunk beyond it. Per-transform costs (parsing set-up, transform context, extension
  // set-up) are then paid per batch, not per workingstep. 0: one transform per chunk.
  // The program's first chunk opens the first batch like any other: rendered alone it cost a
  // transform of its own, a twentieth of a small program's post (docs/render.md).
  std::size_t batch_bytes = std::size_t{64} << 10;
  // A batch is also rendered at the first chunk boundary after it has been open this long, so
  // text keeps flowing while a slow interpretation fills it. 0: no time limit.
  std::chrono::milliseconds batch_delay{50};
  // KIN-005 warnings (a large rotary motion) reported per program at most; the rest are
  // dropped (docs/kinematics.md).
  std::size_t max_kinematics_warnings = 100;
  // The job's cancel flag, which the stylesheet's transforms poll (xslt::JobState::set_cancel):
  // a cancelled job's transform stops within a few milliseconds. Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

class Renderer final : public canon::Sink {
 public:
  // `profile` must outlive the renderer. `input_name` names the program in diagnostics.
  Renderer(const profile::LoadedProfile& profile, TextSink out, RenderOptions options = {},
           std::string input_name = "program");
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;
  ~Renderer() override;

  void call(const canon::Call& call) override;
  // Renders what is left (the end chunk). Once.
  void finish();
  // Renders the calls gathered so far now, as a chunk of their own (with batch_bytes 0: one
  // transform), so that a caller can tell which text came from which calls. Stylesheets that
  // look ahead within a transform may then write other (equivalent) text (docs/render.md).
  void flush();

  // Limit violations (RENDER-001), conversions (RENDER-003/004/005), transform failures
  // (RENDER-002 + the XSLT diagnostics, with the stylesheet's file).
  [[nodiscard]] const std::vector<diag::FileDiagnostic>& diagnostics() const noexcept {
    return diagnostics_;
  }
  [[nodiscard]] bool failed() const noexcept { return failed_; }
  // Whether a transform stopped because RenderOptions::cancel was set (failed() too, with no
  // diagnostic of its own).
  [[nodiscard]] bool cancelled() const noexcept { return cancelled_; }
  // Whether any text was handed to `out` yet.
  [[nodiscard]] bool started() const noexcept { return started_; }
  // Time spent in the stylesheet's transforms so far (a post's render stage; the calls' way
  // into the transforms' input is not in it).
  [[nodiscard]] std::chrono::nanoseconds transform_time() const noexcept { return transform_time_; }

 private:
  class ChunkRenderer;
  class TreeEvents;
  class RunTaker;
  [[nodiscard]] std::optional<canon::Call> honoured_options(const canon::Begin& b);
  void forward(const canon::Call& call);
  void pass(const canon::Call& call);
  void check_limits(const canon::Call& call);
  void check_point(double x, double y, double z, const canon::Call& call);
  void report(diag::Code code, diag::Severity severity, std::string message);
  void render_chunk(const canon::ChunkView& chunk);
  void transform_chunk(const canon::ChunkView& chunk);
  void render_batch();
  bool transform_tree(const std::string& name, std::uint64_t first_seq);
  void emit(std::string& text);
  [[nodiscard]] std::string where(const canon::Call& call) const;

  const profile::LoadedProfile& profile_;
  TextSink out_;
  std::string input_name_;
  xslt::JobState job_;
  xslt::Params params_;
  canon::XmlChunkWriter xml_writer_;
  // The chunk or batch being written: its XML built as the transform's input tree.
  xslt::InputTree tree_;
  std::unique_ptr<TreeEvents> tree_events_;
  // Motions written as runs into tree_ (profile render.motion_runs), for ext:motion-run.
  std::vector<xslt::RunMotion> run_motions_;
  std::unique_ptr<RunTaker> run_taker_;  // null when the profile asks for no runs
  std::unique_ptr<ChunkRenderer> chunk_sink_;
  std::unique_ptr<canon::Chunker> chunker_;
  std::vector<diag::FileDiagnostic> diagnostics_;
  std::optional<canon::Entity> workingstep_;
  std::uint8_t options_reported_ = 0;  // RENDER-011 given, per canon::OutputOption bit
  // The profile's kinematics (profile.json "kinematics"): every call is converted before the
  // limits are checked and the stylesheet sees it (docs/kinematics.md). Null without.
  std::unique_ptr<KinematicsConverter> kinematics_;
  std::vector<KinematicsConverter::Issue> kinematics_warnings_;
  std::size_t kinematics_warning_count_ = 0;
  std::size_t max_kinematics_warnings_ = 0;
  std::int32_t tool_ = 0;  // in the spindle after the chunks rendered so far
  double unit_mm_ = 1.0;   // the program's length unit, in mm
  std::size_t limit_reports_ = 0;
  bool single_chunk_ = false;
  std::vector<canon::Call> whole_;
  // The batch being gathered: its XML (in tree_, an open <chunk>), its calls and chunk ends
  // (to re-render it chunk by chunk if it fails), and the state at its start.
  std::size_t batch_bytes_ = 0;
  std::chrono::milliseconds batch_delay_{0};
  std::chrono::nanoseconds transform_time_{0};
  std::vector<canon::Call> batch_calls_;
  std::vector<std::pair<std::uint64_t, std::size_t>> batch_chunks_;  // seq, end in batch_calls_
  xslt::JobState batch_job_;
  canon::XmlChunkWriter batch_writer_;
  std::int32_t batch_tool_ = 0;
  std::chrono::steady_clock::time_point batch_started_{};
  bool in_batch_ = false;  // render_batch() is running
  bool failed_ = false;
  bool cancelled_ = false;
  bool started_ = false;
  bool finished_ = false;
};

// Renders a whole program held in memory (tests; small programs). Returns the text;
// diagnostics are appended to `diagnostics`.
[[nodiscard]] std::string render_program(const profile::LoadedProfile& profile,
                                         std::span<const canon::Call> calls,
                                         std::vector<diag::FileDiagnostic>& diagnostics,
                                         RenderOptions options = {});

}  // namespace ncpost::render
