#include "ncpost/pipeline/post.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "ncpost/render/raw.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::pipeline {
namespace {

// Passes calls on until the job is cancelled; after that the renderer sees nothing more, so a
// long workingstep does not keep a worker busy for a client that is gone.
class CancellableSink final : public canon::Sink {
 public:
  CancellableSink(canon::Sink& next, const std::atomic<bool>* cancel)
      : next_(next), cancel_(cancel) {}
  void call(const canon::Call& call) override {
    if (cancelled()) return;
    next_.call(call);
  }
  [[nodiscard]] bool cancelled() const {
    return cancel_ != nullptr && cancel_->load(std::memory_order_relaxed);
  }

 private:
  canon::Sink& next_;
  const std::atomic<bool>* cancel_;
};

// The renderer on a thread of its own: the interpreter's calls are handed over in batches
// through a bounded queue, so interpretation and rendering of a large program share two cores
// (each was about a quarter and a third of a post's time). The renderer sees the same calls in
// the same order, so its text is the same; the queue holds at most kMaxBatches batches, so
// memory stays bounded by the model plus a few thousand calls.
class RenderThread final : public canon::Sink {
 public:
  RenderThread(render::Renderer& renderer, const std::atomic<bool>* cancel, std::size_t batch)
      : renderer_(renderer),
        cancel_(cancel),
        batch_calls_(std::max<std::size_t>(1, batch)),
        thread_([this] { run(); }) {
    batch_.reserve(batch_calls_);
  }
  RenderThread(const RenderThread&) = delete;
  RenderThread& operator=(const RenderThread&) = delete;
  // An interpreter that threw: the thread is stopped, nothing is rethrown.
  ~RenderThread() override { stop(false); }

  void call(const canon::Call& call) override {
    batch_.push_back(call);
    if (batch_.size() >= batch_calls_) hand_over();
  }

  // Renders what is still to come and then, when `complete`, calls Renderer::finish(); joins.
  // True when the renderer was finished (false: not complete, or the job was cancelled
  // meanwhile). A renderer that threw has its exception rethrown here, on the caller's thread.
  [[nodiscard]] bool finish(bool complete) {
    stop(complete);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    return finished_;
  }

 private:
  static constexpr std::size_t kMaxBatches = 4;

  void stop(bool complete) {
    if (!thread_.joinable()) return;
    if (complete) hand_over();
    {
      std::lock_guard lock(mutex_);
      done_ = true;
      finish_renderer_ = complete;
    }
    ready_.notify_one();
    thread_.join();
  }

  [[nodiscard]] bool cancelled() const {
    return cancel_ != nullptr && cancel_->load(std::memory_order_relaxed);
  }

  void hand_over() {
    if (batch_.empty()) return;
    {
      std::unique_lock lock(mutex_);
      space_.wait(lock, [&] { return queue_.size() < kMaxBatches; });
      queue_.push_back(std::move(batch_));
    }
    ready_.notify_one();
    batch_ = {};
    batch_.reserve(batch_calls_);
  }

  void run() {
    bool finish_renderer = false;
    for (;;) {
      std::vector<canon::Call> batch;
      {
        std::unique_lock lock(mutex_);
        ready_.wait(lock, [&] { return !queue_.empty() || done_; });
        if (queue_.empty()) {
          finish_renderer = finish_renderer_;
          break;
        }
        batch = std::move(queue_.front());
        queue_.pop_front();
      }
      space_.notify_one();
      // After a failure, or once the job is cancelled, the rest is only drained.
      if (failure_ || cancelled()) continue;
      try {
        for (const auto& call : batch) renderer_.call(call);
      } catch (...) {
        failure_ = std::current_exception();
      }
    }
    if (!finish_renderer || failure_ || cancelled()) return;
    try {
      renderer_.finish();
      finished_ = true;
    } catch (...) {
      failure_ = std::current_exception();
    }
  }

  render::Renderer& renderer_;
  const std::atomic<bool>* cancel_;
  const std::size_t batch_calls_;
  std::vector<canon::Call> batch_;  // the interpreter's thread only
  std::mutex mutex_;
  std::condition_variable ready_;  // a batch was queued, or done_
  std::condition_variable space_;  // a batch was taken
  std::deque<std::vector<canon::Call>> queue_;
  bool done_ = false;
  bool finish_renderer_ = false;
  std::exception_ptr failure_;  // the render thread's until joined
  bool finished_ = false;       // likewise
  std::thread thread_;          // last: started once everything above exists
};

std::string first_error(const std::vector<diag::FileDiagnostic>& diagnostics) {
  for (const auto& d : diagnostics)
    if (d.diagnostic.severity == diag::Severity::Error)
      return std::string(d.diagnostic.code_id()) + " " + d.diagnostic.message;
  return {};
}

}  // namespace

std::string error_marker(const profile::Profile& profile, std::string_view message) {
  const std::string allowed = xslt::CommentRules{}.allowed;
  std::string safe(message);
  for (char& ch : safe)
    if (allowed.find(ch) == std::string::npos) ch = ' ';
  std::string marker = profile.error_marker;
  const std::string_view placeholder = "{message}";
  if (const auto at = marker.find(placeholder); at != std::string::npos)
    marker.replace(at, placeholder.size(), safe);
  return marker + profile.line_ending;
}

namespace {

// Passes calls to the renderer and notes, at each workingstep's Begin and End, how much
// program text exists. With one transform per chunk (RenderOptions::batch_bytes = 0) the
// renderer emits a chunk's text when the chunker closes it, so the text of workingstep k starts
// at the mark taken right after its Begin was passed on; blocks between workingsteps belong to
// the one before. With `per_call` every call is flushed as a chunk of its own before and after
// it is passed on, so each motion's text (and the text where a renderer diagnostic arose) is
// known exactly.
class TextTracker final : public canon::Sink {
 public:
  TextTracker(canon::Sink& next, render::Renderer& renderer, const std::string& text,
              const PostOptions& options)
      : next_(next),
        renderer_(renderer),
        text_(text),
        options_(options),
        per_call_(options.motion_marks != nullptr || options.render_diagnostic_marks != nullptr) {}
  void call(const canon::Call& call) override {
    const std::size_t diagnostics = renderer_.diagnostics().size();
    if (per_call_) renderer_.flush();
    const std::size_t begin = text_.size();
    next_.call(call);
    if (per_call_) renderer_.flush();
    if (options_.motion_marks != nullptr && canon::is_motion(call))
      options_.motion_marks->push_back({begin, text_.size()});
    if (options_.render_diagnostic_marks != nullptr)
      for (std::size_t d = diagnostics; d < renderer_.diagnostics().size(); ++d)
        options_.render_diagnostic_marks->push_back(begin);
    if (options_.workingstep_marks == nullptr) return;
    if (const auto* b = std::get_if<canon::Begin>(&call);
        b != nullptr && b->scope == canon::Scope::Workingstep)
      options_.workingstep_marks->push_back(
          {per_call_ ? begin : text_.size(), b->entity.id, b->entity.name});
    else if (const auto* e = std::get_if<canon::End>(&call);
             e != nullptr && e->scope == canon::Scope::Workingstep)
      options_.workingstep_marks->push_back({text_.size(), 0, {}});
  }

 private:
  canon::Sink& next_;
  render::Renderer& renderer_;
  const std::string& text_;
  const PostOptions& options_;
  bool per_call_;
};

// Runs an interpreter into the sink it is given; the post does not care which one.
using InterpretInto = std::function<Interpretation(canon::Sink& sink)>;

PostResult post_calls(const InterpretInto& interpret_into, std::size_t instances,
                      const profile::LoadedProfile& profile, const render::TextSink& out,
                      const PostOptions& options) {
  const auto started_at = std::chrono::steady_clock::now();
  PostResult result;
  render::RenderOptions render_options = options.render;
  render_options.cancel = options.cancel;
  // The marks need the text as it grows: it is gathered here and handed on at the end.
  std::string marked_text;
  const bool marking = options.workingstep_marks != nullptr || options.motion_marks != nullptr ||
                       options.render_diagnostic_marks != nullptr;
  if (marking) render_options.batch_bytes = 0;
  const render::TextSink renderer_out =
      marking ? render::TextSink([&marked_text](std::string_view piece) { marked_text += piece; })
              : out;
  render::Renderer renderer(profile, renderer_out, render_options, options.input_name);
  const bool two_threads = !marking && options.render_thread_min_instances > 0 &&
                           instances >= options.render_thread_min_instances;
  std::optional<RenderThread> render_thread;
  if (two_threads) render_thread.emplace(renderer, options.cancel, options.render_thread_batch);
  canon::Sink& rendering =
      two_threads ? static_cast<canon::Sink&>(*render_thread) : static_cast<canon::Sink&>(renderer);
  std::optional<TextTracker> tracker;
  if (marking) tracker.emplace(renderer, renderer, marked_text, options);
  CancellableSink sink(marking ? static_cast<canon::Sink&>(*tracker) : rendering, options.cancel);
  const auto interpret_began = std::chrono::steady_clock::now();
  Interpretation interpreted = interpret_into(sink);
  const auto interpret_time = std::chrono::steady_clock::now() - interpret_began;
  result.cancelled = sink.cancelled();
  if (render_thread) {
    // Cancelled while the last batches were rendered: they were skipped, and so is finish().
    result.cancelled = !render_thread->finish(!result.cancelled);
  } else if (!result.cancelled) {
    renderer.finish();
  }
  result.cancelled = result.cancelled || renderer.cancelled();  // during a transform
  result.calls = interpreted.calls;
  result.diagnostics = std::move(interpreted.diagnostics);
  result.diagnostics.insert(result.diagnostics.end(), renderer.diagnostics().begin(),
                            renderer.diagnostics().end());
  result.ok = !result.cancelled && interpreted.ok && !renderer.failed();
  result.started = renderer.started();
  if (marking && !marked_text.empty()) out(marked_text);
  if (!result.ok && result.started) {
    const std::string why =
        result.cancelled ? "the job was cancelled" : first_error(result.diagnostics);
    out(error_marker(profile.profile, why));
  }
  result.interpret_and_render = std::chrono::steady_clock::now() - started_at;
  result.render = renderer.transform_time();
  result.interpret = render_thread ? std::chrono::nanoseconds(interpret_time)
                                   : std::max(std::chrono::nanoseconds{0},
                                              result.interpret_and_render - result.render);
  return result;
}

// Raw mode: the stylesheet reads the model itself (the XSLT paper's post-processor): no
// interpretation, one transform, the text in one piece only when it succeeded.
PostResult post_raw(const LoadedModel& loaded, const profile::LoadedProfile& profile,
                    const render::TextSink& out, const PostOptions& options) {
  const auto started_at = std::chrono::steady_clock::now();
  PostResult result;
  if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) {
    result.cancelled = true;
    return result;
  }
  auto raw = render::render_raw(loaded.model, loaded.schema, profile, out, options.input_name,
                                options.cancel);
  result.diagnostics = std::move(raw.diagnostics);
  result.cancelled = raw.cancelled;
  result.ok = raw.ok;
  result.started = raw.started;
  result.interpret_and_render = std::chrono::steady_clock::now() - started_at;
  result.render = result.interpret_and_render;
  return result;
}

}  // namespace

PostResult post(const LoadedModel& loaded, const profile::LoadedProfile& profile,
                const render::TextSink& out, const PostOptions& options) {
  if (profile.profile.mode == profile::Mode::Raw) return post_raw(loaded, profile, out, options);
  stepnc::InterpretOptions interpret_options;
  interpret_options.tools = options.tools;
  interpret_options.stop_at_first_error = true;
  interpret_options.cancel = options.cancel;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema, loaded.mode);
  const auto interpret_into = [&](canon::Sink& sink) {
    const stepnc::InterpretResult interpreted =
        stepnc::interpret(loaded.model, attributes, sink, interpret_options);
    return Interpretation{diag::with_file(interpreted.diagnostics, options.input_name),
                          interpreted.calls, interpreted.ok()};
  };
  return post_calls(interpret_into, loaded.model.instances().size(), profile, out, options);
}

PostResult post(const Program& program, const JobContext& context,
                const profile::LoadedProfile& profile, const render::TextSink& out,
                const PostOptions& options) {
  PostOptions with_context = options;
  with_context.input_name = program.name;
  with_context.cancel = context.cancel;
  if (profile.profile.mode == profile::Mode::Raw)
    return post_raw(program.loaded, profile, out, with_context);
  InterpretSettings settings;
  settings.stop_at_first_error = true;
  if (options.shop_checks) settings.checks_of = &profile;
  settings.limits_of = &profile;
  const auto interpret_into = [&](canon::Sink& sink) {
    return interpret(program, sink, context, settings);
  };
  return post_calls(interpret_into, program.loaded.model.instances().size(), profile, out,
                    with_context);
}

std::vector<diag::FileDiagnostic> PostJobResult::diagnostics() const {
  std::vector<diag::FileDiagnostic> all = read.diagnostics;
  all.insert(all.end(), post.diagnostics.begin(), post.diagnostics.end());
  return all;
}

PostJobResult post(Input input, const JobContext& context, const profile::LoadedProfile& profile,
                   const render::TextSink& out, const PostOptions& options, const OnRead& on_read) {
  PostJobResult result;
  Program program = read(std::move(input), context);
  if (profile.profile.mode == profile::Mode::Raw && program.ok())
    (void)require_model(program, "a raw profile (" + profile.profile.id + ")",
                        "choose a profile that writes G-code");
  result.read = read_result(program);
  if (!result.read.ok) return result;
  if (on_read) on_read(result.read);
  result.post = post(program, context, profile, out, options);
  return result;
}

}  // namespace ncpost::pipeline
