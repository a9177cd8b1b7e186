#include "cli_support.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::cli {

Options::Options(Args args, std::vector<std::string_view> value_options) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string_view arg = args[i];
    if (arg.size() > 2 && arg.substr(0, 2) == "--") {
      std::string_view name = arg.substr(2);
      std::optional<std::string_view> inline_value;
      if (auto eq = name.find('='); eq != std::string_view::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      const bool takes_value =
          std::find(value_options.begin(), value_options.end(), name) != value_options.end();
      if (takes_value) {
        if (inline_value) {
          values_.emplace_back(name, *inline_value);
        } else if (i + 1 < args.size()) {
          values_.emplace_back(name, args[++i]);
        } else {
          error_ = "option --" + std::string(name) + " needs a value";
        }
      } else if (inline_value) {
        error_ = "option --" + std::string(name) + " takes no value";
      } else {
        flags_.emplace_back(name);
      }
    } else {
      positionals_.emplace_back(arg);
    }
  }
}

std::optional<std::string> Options::value(std::string_view name) const {
  for (auto it = values_.rbegin(); it != values_.rend(); ++it)
    if (it->first == name) return it->second;
  return std::nullopt;
}

bool Options::flag(std::string_view name) const {
  return std::find(flags_.begin(), flags_.end(), name) != flags_.end();
}

std::optional<Input> read_input(const std::string& path) {
  Input input;
  if (path == "-") {
    input.name = "<stdin>";
    std::ostringstream ss;
    ss << std::cin.rdbuf();
    input.bytes = std::move(ss).str();
    return input;
  }
  input.name = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const diag::Diagnostic d = diag::make(diag::Code::IoCannotRead, 0, 0,
                                          "cannot open '" + path + "': " + std::strerror(errno));
    std::cerr << diag::format(d, path) << '\n';
    return std::nullopt;
  }
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0) input.bytes.resize(static_cast<std::size_t>(size));
  in.read(input.bytes.data(), static_cast<std::streamsize>(input.bytes.size()));
  if (!in && !in.eof()) {
    const diag::Diagnostic d =
        diag::make(diag::Code::IoCannotRead, 0, 0, "cannot read '" + path + "'");
    std::cerr << diag::format(d, path) << '\n';
    return std::nullopt;
  }
  return input;
}

void print_diagnostics(const std::vector<diag::Diagnostic>& diagnostics, std::string_view file) {
  for (const auto& d : diagnostics) std::cerr << diag::format(d, file) << '\n';
}

bool has_errors(const std::vector<diag::Diagnostic>& diagnostics) {
  return diag::has_errors(diagnostics);
}

int usage_error(std::string_view verb, std::string_view message) {
  std::cerr << "ncpost " << verb << ": " << message << "\n(run 'ncpost help' for usage)\n";
  return kExitUsage;
}

LoadedSchemas load_schemas(const std::optional<std::string>& directory) {
  LoadedSchemas loaded;
  if (directory) loaded.reports = loaded.registry.add_directory(*directory);
  return loaded;
}

void print_schema_reports(const std::vector<express::SchemaFileReport>& reports) {
  for (const auto& report : reports) print_diagnostics(report.diagnostics, report.file.string());
}

bool has_errors(const std::vector<express::SchemaFileReport>& reports) {
  return std::any_of(reports.begin(), reports.end(),
                     [](const auto& report) { return has_errors(report.diagnostics); });
}

void add_builtin_report(LoadedSchemas& schemas, const pipeline::LoadedModel& loaded) {
  const express::SchemaSource& builtin = schemas.registry.builtin();
  if (loaded.schema != &builtin.set()) return;
  auto problems = schemas.registry.builtin_diagnostics();
  if (!problems.empty()) schemas.reports.push_back({builtin.origin, std::move(problems)});
}

pipeline::LoadedModel load_on_all_cores(std::string bytes, const express::SchemaRegistry& schemas,
                                        bool validate) {
  const parallel::ThreadGroup threads(parallel::spare_cores());
  pipeline::LoadOptions options;
  options.validate = validate;
  options.helpers = &threads.helpers();
  return pipeline::load(std::move(bytes), schemas, options);
}

std::optional<ProgramJob> load_program_job(const Options& options) {
  ProgramJob job;
  job.schemas = load_schemas(options.value("schemas"));
  if (const auto table = options.value("tools")) {
    auto text = read_input(*table);
    if (!text) return std::nullopt;
    std::vector<diag::Diagnostic> table_diagnostics;
    job.interpret.tools = stepnc::read_tool_table(text->bytes, table_diagnostics);
    print_diagnostics(table_diagnostics, *table);
    if (has_errors(table_diagnostics)) return std::nullopt;
  }
  auto input = read_input(options.positionals().front());
  if (!input) {
    print_schema_reports(job.schemas.reports);
    return std::nullopt;
  }
  job.name = input->name;
  job.loaded = load_on_all_cores(std::move(input->bytes), job.schemas.registry);
  add_builtin_report(job.schemas, job.loaded);
  print_schema_reports(job.schemas.reports);
  // A schema directory that cannot be read, or a broken built-in, stops the job as inspect does.
  if (has_errors(job.schemas.reports)) return std::nullopt;
  if (!job.loaded.ok()) {
    // Say what the file is, too, when it is not a program at all (an AP238 AIM excerpt, say).
    if (job.loaded.model.instances_of("PROJECT").empty())
      job.loaded.diagnostics.push_back(stepnc::no_program_diagnostic(job.loaded.model));
    print_diagnostics(job.loaded.diagnostics, job.name);
    return std::nullopt;
  }
  return job;
}

}  // namespace ncpost::cli
