#pragma once
// Raw mode (profile "mode": "raw"): the XSLT post-processor paper's way. The whole model is
// written as one late-bound P28 document (engine/p28, the paper's fig. 6 form) and the profile's
// stylesheet runs once on it, navigating the instance graph itself (project → workplan →
// workingsteps → operations → toolpaths, references followed by id). No interpretation, no
// chunks: memory grows with the document. docs/render.md, raw mode.

#include <string>
#include <string_view>
#include <vector>

#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::render {

struct RawResult {
  // RENDER-006 (the document is too large), RENDER-002 and the XSLT diagnostics (with the
  // stylesheet's file) when the transform fails, P28 notes about entities the schema lacks.
  std::vector<diag::FileDiagnostic> diagnostics;
  bool ok = false;
  bool started = false;    // text reached `out`
  bool cancelled = false;  // `cancel` was set during the transform: not ok, nothing written
};

// The model as the late-bound P28 document the stylesheet reads (tests, `ncpost convert`
// gives the same text). Appends P28 notes to `diagnostics`.
[[nodiscard]] std::string raw_document(const p21::Model& model, const express::SchemaSet* schemas,
                                       std::vector<diag::FileDiagnostic>& diagnostics,
                                       std::string_view input_name);

// Transforms `model` with a raw-mode profile: one transform with the profile's JobState (number
// formats, set-up, block numbers) and parameters (program_number, profile_id), the xslt stage's
// security and limits (xslt::Limits::max_input_bytes bounds the document). The output goes to
// `out` in one piece, with the profile's line ending, only if the transform succeeded. The
// transform polls `cancel` (null: never cancelled).
[[nodiscard]] RawResult render_raw(const p21::Model& model, const express::SchemaSet* schemas,
                                   const profile::LoadedProfile& profile, const TextSink& out,
                                   std::string_view input_name = "program",
                                   const std::atomic<bool>* cancel = nullptr);

}  // namespace ncpost::render
