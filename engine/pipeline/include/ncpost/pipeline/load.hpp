#pragma once
// The front of every job: detect → read (P21 or P28) → choose the schema → check the model
// against it. The CLI verbs and the server share it, so they treat an upload the same way.

#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "ncpost/pipeline/detect.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace ncpost::p21 {
class StreamReader;
}

namespace ncpost::pipeline {

struct LoadOptions {
  // Check the model against its schema (skipped for a fallback schema, where every instance
  // would be reported).
  bool validate = true;
  // Set by another thread to stop the job: passed to the P21 reader and the schema check.
  const std::atomic<bool>* cancel = nullptr;
  // Threads lent to read and check a large file in pieces (null: one thread); the result is the
  // same either way.
  const parallel::Helpers* helpers = nullptr;
  // The schema check reports what the interpreter checks again as aggregated warnings
  // (express::ValidateOptions::tolerant); a job sets it unless JobContext::strict. Tolerant, the
  // variants table (stepnc/variants.hpp) also names the schema of FILE_SCHEMA names such as
  // COMBINED_SCHEMA, and the check reads its entity aliases.
  bool tolerant = false;
};

struct LoadedModel {
  InputFormat format = InputFormat::Unknown;
  p21::Model model;
  // Never null after load(): the schema FILE_SCHEMA names, or the built-in as a fallback.
  const express::SchemaSet* schema = nullptr;
  bool schema_is_fallback = false;
  // How the model is to be read: LoadOptions::tolerant. Every AttributeReader of a job over this
  // model takes it (stepnc::AttributeReader's mode).
  stepnc::Mode mode = stepnc::Mode::Strict;
  // Reading, schema choice (EXP-050/052) and, unless the schema is a fallback, the check of the
  // model against it, in that order.
  std::vector<diag::Diagnostic> diagnostics;
  // Stopped by LoadOptions::cancel: nothing else here means anything.
  bool cancelled = false;
  std::chrono::nanoseconds read_time{0};   // the text into a model (what was left of it)
  std::chrono::nanoseconds check_time{0};  // schema choice and the check against it
  [[nodiscard]] bool ok() const;
};

[[nodiscard]] LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas,
                               const LoadOptions& options);
[[nodiscard]] LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas,
                               bool validate = true);
// The same, for an upload that `streamed` has been reading while it arrived (every byte of it
// appended by now). Input that turns out not to be P21 is taken back and loaded as above.
[[nodiscard]] LoadedModel load(p21::StreamReader& streamed, const express::SchemaRegistry& schemas,
                               const LoadOptions& options);

}  // namespace ncpost::pipeline
