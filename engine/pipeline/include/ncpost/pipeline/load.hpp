#pragma once
// The front of every job: detect → read (P21 or P28) → choose the schema → check the model
// against it. The CLI verbs and the server share it, so they treat an upload the same way.

#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/pipeline/detect.hpp"

namespace ncpost::pipeline {

struct LoadedModel {
  InputFormat format = InputFormat::Unknown;
  p21::Model model;
  // Never null after load(): the schema FILE_SCHEMA names, or the built-in as a fallback.
  const express::SchemaSet* schema = nullptr;
  bool schema_is_fallback = false;
  // Reading, schema choice (EXP-050/052) and, unless the schema is a fallback, the check of the
  // model against it, in that order.
  std::vector<diag::Diagnostic> diagnostics;
  [[nodiscard]] bool ok() const;
};

// `validate`: check the model against its schema (skipped for a fallback schema, where every
// instance would be reported).
[[nodiscard]] LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas,
                               bool validate = true);

}  // namespace ncpost::pipeline
