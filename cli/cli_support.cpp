#include "cli_support.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

namespace ncpost::cli {
namespace {

const OptionSpec* find_option(const VerbSpec& spec, std::string_view name) {
  for (const OptionSpec& option : spec.options)
    if (option.name == name) return &option;
  return nullptr;
}

void print_io_error(const std::string& path, std::string message) {
  std::cerr << diag::format(diag::make(diag::Code::IoCannotRead, 0, 0, std::move(message)), path)
            << '\n';
}

// The regular files of `directory`, by name, as a G-code program's subprogram files; sorted so
// that which of two files of one name wins does not depend on the file system.
std::optional<std::vector<pipeline::SourceFile>> read_subprograms(const std::string& directory) {
  std::error_code ec;
  std::vector<std::filesystem::path> paths;
  for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end;
       it.increment(ec))
    if (it->is_regular_file(ec)) paths.push_back(it->path());
  if (ec) {
    print_io_error(directory,
                   "cannot read the subprogram folder '" + directory + "': " + ec.message());
    return std::nullopt;
  }
  std::sort(paths.begin(), paths.end());
  std::vector<pipeline::SourceFile> files;
  for (const auto& path : paths) {
    auto file = read_input(path.string());
    if (!file) return std::nullopt;
    files.push_back({path.filename().string(), std::move(file->bytes)});
  }
  return files;
}

}  // namespace

Options::Options(Args args, const VerbSpec& spec) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string_view arg = args[i];
    if (arg == "--help" || arg == "-h") {
      help_ = true;
      continue;
    }
    if (arg.size() < 2 || arg.substr(0, 2) != "--") {
      if (arg.size() > 1 && arg.front() == '-' && error_.empty())
        error_ = "unknown option " + std::string(arg);
      else
        positionals_.emplace_back(arg);
      continue;
    }
    std::string_view name = arg.substr(2);
    std::optional<std::string_view> inline_value;
    if (auto eq = name.find('='); eq != std::string_view::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const OptionSpec* option = find_option(spec, name);
    if (!error_.empty()) continue;  // the first problem is the one reported
    if (option == nullptr) {
      error_ = "unknown option --" + std::string(name);
    } else if (option->value_name.empty()) {
      if (inline_value)
        error_ = "option --" + std::string(name) + " takes no value";
      else
        flags_.emplace_back(name);
    } else if (inline_value) {
      values_.emplace_back(name, *inline_value);
    } else if (i + 1 < args.size()) {
      values_.emplace_back(name, args[++i]);
    } else {
      error_ = "option --" + std::string(name) + " needs a value";
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

int print_help(const VerbSpec& spec) {
  std::cout << "usage: ncpost " << spec.usage;
  return kExitOk;
}

int usage_error(const VerbSpec& spec, std::string_view message) {
  std::cerr << "ncpost " << spec.name << ": " << message << "\nusage: ncpost " << spec.usage;
  return kExitUsage;
}

std::optional<int> parse_or_exit(const Options& options, const VerbSpec& spec, std::size_t files) {
  if (options.help()) return print_help(spec);
  if (!options.error().empty()) return usage_error(spec, options.error());
  if (options.positionals().size() != files)
    return usage_error(spec, files == 0 ? "takes no FILE" : "expects one FILE or -");
  return std::nullopt;
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
    print_io_error(path, "cannot open '" + path + "': " + std::strerror(errno));
    return std::nullopt;
  }
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0) input.bytes.resize(static_cast<std::size_t>(size));
  in.read(input.bytes.data(), static_cast<std::streamsize>(input.bytes.size()));
  if (!in && !in.eof()) {
    print_io_error(path, "cannot read '" + path + "'");
    return std::nullopt;
  }
  return input;
}

void print_diagnostics(const std::vector<diag::FileDiagnostic>& diagnostics) {
  for (const auto& d : diagnostics) std::cerr << diag::format(d) << '\n';
}

void write_stdout(std::string_view piece) {
  std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
}

std::unique_ptr<pipeline::Profiles> open_profiles(const Options& options) {
  const auto directory = options.value("profiles");
  return directory ? pipeline::Profiles::read_only(*directory)
                   : std::make_unique<pipeline::Profiles>();
}

std::unique_ptr<CliJob> prepare_job(const Options& options) {
  auto job = std::make_unique<CliJob>();
  if (const auto directory = options.value("schemas"))
    job->schemas = pipeline::load_schemas(std::filesystem::path(*directory));
  job->context.schemas = &job->schemas;
  job->context.strict = options.flag("strict");
  if (const auto table = options.value("tools")) {
    const auto text = read_input(*table);
    if (!text) return nullptr;
    pipeline::ToolTableResult tools = pipeline::read_tool_table(text->bytes, text->name);
    print_diagnostics(tools.diagnostics);
    if (!tools.table) return nullptr;
    job->context.tools = std::move(tools.table);
  }
  if (auto dialect = options.value("dialect") ? options.value("dialect") : options.value("from")) {
    const pipeline::ProfileLookup lookup = open_profiles(options)->find(*dialect);
    print_diagnostics(lookup.diagnostics);
    if (!lookup.profile) return nullptr;
    job->context.gcode_dialect = lookup.profile;
  }
  if (const auto directory = options.value("subprograms")) {
    auto files = read_subprograms(*directory);
    if (!files) return nullptr;
    job->context.gcode_subprograms =
        std::make_shared<const std::vector<pipeline::SourceFile>>(std::move(*files));
  }
  auto input = read_input(options.positionals().front());
  if (!input) {
    print_diagnostics(job->schemas.reports);
    return nullptr;
  }
  job->input.name = std::move(input->name);
  job->input.bytes = std::move(input->bytes);
  // Reading and checking a large file uses every core; the result is the same as on one.
  job->threads = std::make_unique<pipeline::ThreadGroup>(pipeline::spare_cores());
  job->context.helpers = &job->threads->helpers();
  std::ios::sync_with_stdio(false);
  return job;
}

}  // namespace ncpost::cli
