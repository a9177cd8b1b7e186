#pragma once
// A post job: read the input, interpret it and render it through one machine profile, handing
// controller text to `out` chunk by chunk as it is ready. `ncpost post` and ncpostd's
// POST /v1/posts both run this, so a program posted either way is byte-identical.

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/pipeline/block_map.hpp"
#include "ncpost/pipeline/job.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::pipeline {

struct PostOptions {
  std::string input_name = "program";  // names the program in diagnostics
  std::optional<stepnc::ToolTable> tools;
  render::RenderOptions render{};
  // Set by another thread to stop the job (client gone, time limit): checked between
  // executables and before each chunk is handed on. Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
  // A model of at least this many instances is rendered on a second thread while it is
  // interpreted (docs/architecture.md, "Two threads in a post"): `out` is then called from
  // that thread, one piece at a time and in order as always. Below it, or 0, one thread does
  // both: for a small program a thread costs more than it saves.
  std::size_t render_thread_min_instances = 50000;
  // Calls handed to the render thread at a time (at most four such batches wait).
  std::size_t render_thread_batch = 4096;
  // Non-null: where each workingstep's text begins, for a block → workingstep map
  // (block_map.hpp). Needs one transform per chunk, so the renderer's batching is turned off
  // and the post runs on one thread.
  std::vector<WorkingstepMark>* workingstep_marks = nullptr;
  // Non-null: where each canonical motion's text lies (in program order: the motions of
  // `ncpost trace`), and where the text of the call behind each renderer diagnostic begins
  // (one offset per renderer diagnostic, in order; an error's is where the error marker goes).
  // Every call is then rendered as a chunk of its own, one transform each: slower, and the one
  // profile whose stylesheet looks ahead (heidenhain-tnc640) may write equivalent but other
  // text. Implies the one thread of workingstep_marks.
  std::vector<MotionMark>* motion_marks = nullptr;
  std::vector<std::size_t>* render_diagnostic_marks = nullptr;
  // The profile's pre-post checks on CL input (docs/cls.md); false: `--no-checks`,
  // `checks=false`.
  bool shop_checks = true;
};

struct PostResult {
  // Interpreter and renderer diagnostics, in that order; the renderer's carry the stylesheet's
  // file where they come from it (otherwise the input name).
  std::vector<diag::FileDiagnostic> diagnostics;
  bool ok = false;
  bool started = false;    // some text reached `out`
  bool cancelled = false;  // stopped by PostOptions::cancel
  std::size_t calls = 0;   // canonical calls interpreted
  std::chrono::nanoseconds interpret_and_render{0};
  // Of that, the render stage: the time in the stylesheet's transforms (all of it in raw
  // mode). `interpret` is the rest: the interpretation and the calls' way to the transforms;
  // with a render thread, whose work overlaps it, the interpreter's own time instead (which
  // includes waiting while the render queue is full).
  std::chrono::nanoseconds render{0};
  std::chrono::nanoseconds interpret{0};
};

// Everything a whole post job reports: reading and checking, then the post.
struct PostJobResult {
  JobResult read;   // reading and checking (its diagnostics come first)
  PostResult post;  // empty when reading failed
  [[nodiscard]] bool ok() const { return read.ok && post.ok; }
  // read.diagnostics, then post.diagnostics.
  [[nodiscard]] std::vector<diag::FileDiagnostic> diagnostics() const;
};

// Called once reading and checking succeeded, before any text (ncpostd reports the read's
// timing in the response's head, which goes out with the first text).
using OnRead = std::function<void(const JobResult& read)>;

// The whole job: read(input) (job.hpp), then post() below. Nothing reaches `out` when reading
// fails. `context.tools` replaces options.tools.
[[nodiscard]] PostJobResult post(Input input, const JobContext& context,
                                 const profile::LoadedProfile& profile, const render::TextSink& out,
                                 const PostOptions& options = {}, const OnRead& on_read = {});
// The post of a program already read (which must be ok()).
[[nodiscard]] PostResult post(const Program& program, const JobContext& context,
                              const profile::LoadedProfile& profile, const render::TextSink& out,
                              const PostOptions& options = {});

// Interprets `loaded` (which must be ok()) and renders it with `profile`; a raw-mode profile
// (profile::Mode::Raw) instead transforms the model as one P28 document (render/raw.hpp). The
// interpreter stops at the first error. When the job fails or is cancelled after text went out, the
// last piece is the profile's error marker (profile.error_marker), so that a partial program never
// looks complete to the controller or to the operator.
[[nodiscard]] PostResult post(const LoadedModel& loaded, const profile::LoadedProfile& profile,
                              const render::TextSink& out, const PostOptions& options = {});

// The profile's error marker with `message` made safe for a comment of that controller.
[[nodiscard]] std::string error_marker(const profile::Profile& profile, std::string_view message);

}  // namespace ncpost::pipeline
