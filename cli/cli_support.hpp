#pragma once
// Small helpers shared by the verbs: option parsing, reading FILE or stdin, printing diagnostics.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "verbs.hpp"

namespace ncpost::cli {

// Options of the form `--name value` or `--name=value`, flags `--name`, and positionals.
class Options {
 public:
  // `value_options` are the options that take a value; anything else starting with `--` is a flag.
  Options(Args args, std::vector<std::string_view> value_options);

  [[nodiscard]] std::optional<std::string> value(std::string_view name) const;
  [[nodiscard]] bool flag(std::string_view name) const;
  [[nodiscard]] const std::vector<std::string>& positionals() const { return positionals_; }
  // Non-empty when the command line could not be parsed; a usage error.
  [[nodiscard]] const std::string& error() const { return error_; }

 private:
  std::vector<std::pair<std::string, std::string>> values_;
  std::vector<std::string> flags_;
  std::vector<std::string> positionals_;
  std::string error_;
};

struct Input {
  std::string name;  // for diagnostics: the path, or "<stdin>"
  std::string bytes;
};

// Reads a path, or stdin for "-". On failure returns nullopt and prints an IO-001 diagnostic.
[[nodiscard]] std::optional<Input> read_input(const std::string& path);

void print_diagnostics(const std::vector<diag::Diagnostic>& diagnostics, std::string_view file);
[[nodiscard]] bool has_errors(const std::vector<diag::Diagnostic>& diagnostics);

int usage_error(std::string_view verb, std::string_view message);

// The schemas a verb reads models with: the built-in ISO 14649 schema and, with `--schemas DIR`,
// every .exp file of DIR (parsed once each). `reports` holds the schema files' diagnostics, each
// with its file: a file with errors is left out and the others are still used, but the errors
// are printed and make the exit status 1, so that a typo in --schemas does not go unnoticed.
struct LoadedSchemas {
  express::SchemaRegistry registry;
  std::vector<express::SchemaFileReport> reports;
};
[[nodiscard]] LoadedSchemas load_schemas(const std::optional<std::string>& directory);
// When the model's schema is the built-in, its own problems (EXP-054: a build problem) are added
// to the reports.
void add_builtin_report(LoadedSchemas& schemas, const pipeline::LoadedModel& loaded);
// pipeline::load, reading and checking a large file on every core (the result is the same).
[[nodiscard]] pipeline::LoadedModel load_on_all_cores(std::string bytes,
                                                      const express::SchemaRegistry& schemas,
                                                      bool validate = true);
// Prints each report's diagnostics with its file name.
void print_schema_reports(const std::vector<express::SchemaFileReport>& reports);
[[nodiscard]] bool has_errors(const std::vector<express::SchemaFileReport>& reports);

// What `trace` and `post` interpret: the schemas (--schemas DIR), the tool table (--tools
// TABLE) and the program (the one positional FILE), loaded and checked. Every diagnostic of these
// steps is printed here; nullopt means the job cannot go on (exit status 1).
struct ProgramJob {
  std::string name;  // for diagnostics
  LoadedSchemas schemas;
  pipeline::LoadedModel loaded;
  stepnc::InterpretOptions interpret;
};
[[nodiscard]] std::optional<ProgramJob> load_program_job(const Options& options);

}  // namespace ncpost::cli
