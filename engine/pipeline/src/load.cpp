#include "ncpost/pipeline/load.hpp"

#include <algorithm>

#include "ncpost/express/validate.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p28/p28.hpp"

namespace ncpost::pipeline {

bool LoadedModel::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const auto& d) { return d.severity == diag::Severity::Error; });
}

LoadedModel load(std::string bytes, const express::SchemaRegistry& schemas, bool validate) {
  LoadedModel out;
  out.format = detect_format(bytes);
  p21::ReadResult read;
  if (out.format == InputFormat::P28) {
    p28::ReadOptions options;
    // A P28 document names its schema in its header, which comes first.
    options.schema_for_header = [&](const p21::Model& header) {
      return schemas.select_or_builtin(header).set();
    };
    read = p28::read(bytes, nullptr, options);
  } else {
    read = p21::read(std::move(bytes));
  }
  out.model = std::move(read.model);
  out.diagnostics = std::move(read.diagnostics);
  express::SchemaSelection selection = schemas.select_or_builtin(out.model);
  out.schema = selection.set();
  out.schema_is_fallback = selection.fallback;
  out.diagnostics.insert(out.diagnostics.end(), selection.diagnostics.begin(),
                         selection.diagnostics.end());
  if (validate && !selection.fallback && out.schema != nullptr) {
    auto checked = express::validate(out.model, *out.schema);
    out.diagnostics.insert(out.diagnostics.end(), std::make_move_iterator(checked.begin()),
                           std::make_move_iterator(checked.end()));
  }
  return out;
}

}  // namespace ncpost::pipeline
