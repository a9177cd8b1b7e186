#include "ncpost/pipeline/load.hpp"

#include <algorithm>

#include "ncpost/express/validate.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/stream_reader.hpp"
#include "ncpost/p28/p28.hpp"

namespace ncpost::pipeline {

namespace {

using Clock = std::chrono::steady_clock;

// After reading: the schema the header names (or the built-in), and the check against it.
void check(LoadedModel& out, const express::SchemaRegistry& schemas, const LoadOptions& options) {
  const auto started = Clock::now();
  express::SchemaSelection selection =
      schemas.select_or_builtin(out.model, stepnc::schema_aliases(out.mode));
  out.schema = selection.set();
  out.schema_is_fallback = selection.fallback;
  out.diagnostics.insert(out.diagnostics.end(), selection.diagnostics.begin(),
                         selection.diagnostics.end());
  if (options.validate && !selection.fallback && out.schema != nullptr) {
    express::ValidateOptions validate_options;
    validate_options.cancel = options.cancel;
    validate_options.helpers = options.helpers;
    validate_options.plan = &selection.source->check_plan();
    validate_options.tolerant = options.tolerant;
    validate_options.entity_aliases = stepnc::entity_aliases(out.mode);
    auto checked = express::validate(out.model, *out.schema, validate_options);
    out.diagnostics.insert(out.diagnostics.end(), std::make_move_iterator(checked.begin()),
                           std::make_move_iterator(checked.end()));
  }
  out.cancelled = options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed);
  out.check_time = Clock::now() - started;
}

void take(LoadedModel& out, p21::ReadResult read) {
  out.cancelled = read.cancelled;
  out.model = std::move(read.model);
  out.diagnostics = std::move(read.diagnostics);
}

}  // namespace

bool LoadedModel::ok() const {
  return !cancelled && std::none_of(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
    return d.severity == diag::Severity::Error;
  });
}

LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas,
                 const LoadOptions& options) {
  LoadedModel out;
  out.mode = options.tolerant ? stepnc::Mode::Tolerant : stepnc::Mode::Strict;
  const auto started = Clock::now();
  out.format = detect_format(bytes);
  if (out.format == InputFormat::P28) {
    p28::ReadOptions p28_options;
    p28_options.cancel = options.cancel;
    // A P28 document names its schema in its header, which comes first.
    p28_options.schema_for_header = [&](const p21::Model& header) {
      return schemas.select_or_builtin(header, stepnc::schema_aliases(out.mode)).set();
    };
    take(out, p28::read(bytes, nullptr, p28_options));
  } else {
    p21::ReadOptions p21_options;
    p21_options.cancel = options.cancel;
    p21_options.helpers = options.helpers;
    take(out, p21::read(std::move(bytes), p21_options));
  }
  out.read_time = Clock::now() - started;
  if (out.cancelled) return out;
  check(out, schemas, options);
  return out;
}

LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas, bool validate) {
  LoadOptions options;
  options.validate = validate;
  return load(std::move(bytes), schemas, options);
}

LoadedModel load(p21::StreamReader& streamed, const express::SchemaRegistry& schemas,
                 const LoadOptions& options) {
  const auto started = Clock::now();
  if (detect_format(streamed.arrived(streamed.appended())) != InputFormat::P21)
    return load(streamed.take_text(), schemas, options);
  LoadedModel out;
  out.mode = options.tolerant ? stepnc::Mode::Tolerant : stepnc::Mode::Strict;
  out.format = InputFormat::P21;
  take(out, streamed.finish());
  out.read_time = Clock::now() - started;
  if (out.cancelled) return out;
  check(out, schemas, options);
  return out;
}

}  // namespace ncpost::pipeline
