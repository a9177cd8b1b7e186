#include "ncpost/render/raw.hpp"

#include "ncpost/p28/p28.hpp"

namespace ncpost::render {
namespace {

// The writer streams; the document is gathered because one transform needs all of it. Writing
// stops counting at the xslt stage's input limit, so a huge model fails early with one
// diagnostic instead of building a string the transform would refuse anyway.
struct Gathered {
  std::string text;
  bool too_large = false;
};

Gathered gather(const p21::Model& model, const express::SchemaSet* schemas,
                std::vector<diag::FileDiagnostic>& diagnostics, std::string_view input_name,
                std::size_t max_bytes) {
  Gathered g;
  const auto notes = p28::write(model, schemas, p28::Binding::Late, [&](std::string_view piece) {
    if (g.too_large) return;
    if (g.text.size() + piece.size() > max_bytes) {
      g.too_large = true;
      g.text.clear();
      g.text.shrink_to_fit();
      return;
    }
    g.text.append(piece);
  });
  for (const auto& n : notes) diagnostics.push_back({std::string(input_name), n});
  return g;
}

}  // namespace

std::string raw_document(const p21::Model& model, const express::SchemaSet* schemas,
                         std::vector<diag::FileDiagnostic>& diagnostics,
                         std::string_view input_name) {
  return gather(model, schemas, diagnostics, input_name, xslt::Limits{}.max_input_bytes).text;
}

RawResult render_raw(const p21::Model& model, const express::SchemaSet* schemas,
                     const profile::LoadedProfile& profile, const TextSink& out,
                     std::string_view input_name, const std::atomic<bool>* cancel) {
  RawResult result;
  const xslt::Limits limits{};
  Gathered doc = gather(model, schemas, result.diagnostics, input_name, limits.max_input_bytes);
  if (doc.too_large) {
    result.diagnostics.push_back(
        {std::string(input_name),
         diag::make(diag::Code::RenderRawTooLarge, 0, 0,
                    "the model as a P28 document exceeds " +
                        std::to_string(limits.max_input_bytes) +
                        " bytes, the transform's input limit; raw-mode profiles read the whole "
                        "document at once")});
    return result;
  }
  xslt::JobState job(profile::job_config(profile.profile), limits);
  job.set_cancel(cancel);
  const xslt::Params params{{"program_number", std::to_string(profile.profile.program_number)},
                            {"profile_id", profile.profile.id}};
  auto transformed =
      xslt::transform(*profile.stylesheet, doc.text, job, params, std::string(input_name) + ".p28");
  for (auto& d : transformed.diagnostics) result.diagnostics.push_back(std::move(d));
  if (transformed.cancelled) {
    result.cancelled = true;
    return result;
  }
  if (!transformed.ok) {
    result.diagnostics.push_back(
        {std::string(input_name),
         diag::make(diag::Code::RenderTransform, 0, 0,
                    "the stylesheet of raw-mode profile '" + profile.profile.id +
                        "' failed on the P28 document")});
    return result;
  }
  std::string text = std::move(transformed.output);
  if (profile.profile.line_ending != "\n") {
    std::string converted;
    converted.reserve(text.size() + text.size() / 16);
    for (char ch : text) {
      if (ch == '\n')
        converted += profile.profile.line_ending;
      else
        converted += ch;
    }
    text.swap(converted);
  }
  if (!text.empty()) {
    result.started = true;
    out(text);
  }
  result.ok = !diag::has_errors(result.diagnostics);
  return result;
}

}  // namespace ncpost::render
