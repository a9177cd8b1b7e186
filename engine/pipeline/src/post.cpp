#include "ncpost/pipeline/post.hpp"

#include "ncpost/render/raw.hpp"

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

std::string first_error(const std::vector<xslt::FileDiagnostic>& diagnostics) {
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

PostResult post(const LoadedModel& loaded, const profile::LoadedProfile& profile,
                const render::TextSink& out, const PostOptions& options) {
  const auto started_at = std::chrono::steady_clock::now();
  PostResult result;
  if (profile.profile.mode == profile::Mode::Raw) {
    // The stylesheet reads the model itself (the XSLT paper's post-processor): no
    // interpretation, one transform, the text in one piece only when it succeeded.
    if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) {
      result.cancelled = true;
      return result;
    }
    auto raw = render::render_raw(loaded.model, loaded.schema, profile, out, options.input_name);
    result.diagnostics = std::move(raw.diagnostics);
    result.ok = raw.ok;
    result.started = raw.started;
    result.interpret_and_render = std::chrono::steady_clock::now() - started_at;
    return result;
  }
  stepnc::InterpretOptions interpret_options;
  interpret_options.tools = options.tools;
  interpret_options.stop_at_first_error = true;
  interpret_options.cancel = options.cancel;

  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  render::Renderer renderer(profile, out, options.render, options.input_name);
  CancellableSink sink(renderer, options.cancel);
  const stepnc::InterpretResult interpreted =
      stepnc::interpret(loaded.model, attributes, sink, interpret_options);
  result.cancelled = sink.cancelled();
  if (!result.cancelled) renderer.finish();
  result.calls = interpreted.calls;

  for (const auto& d : interpreted.diagnostics)
    result.diagnostics.push_back({options.input_name, d});
  result.diagnostics.insert(result.diagnostics.end(), renderer.diagnostics().begin(),
                            renderer.diagnostics().end());
  result.ok = !result.cancelled && interpreted.ok() && !renderer.failed();
  result.started = renderer.started();
  if (!result.ok && result.started) {
    const std::string why =
        result.cancelled ? "the job was cancelled" : first_error(result.diagnostics);
    out(error_marker(profile.profile, why));
  }
  result.interpret_and_render = std::chrono::steady_clock::now() - started_at;
  return result;
}

}  // namespace ncpost::pipeline
