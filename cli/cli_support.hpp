#pragma once
// What the verbs share: each verb's declared options (an option a verb does not declare is a
// usage error that names it), `--help`, reading FILE or stdin, printing diagnostics, and the
// set-up of a job (schemas, tool table, threads) that every program-reading verb needs.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/pipeline/job.hpp"
#include "ncpost/pipeline/profiles.hpp"
#include "verbs.hpp"

namespace ncpost::cli {

struct OptionSpec {
  std::string_view name;        // without the leading "--"
  std::string_view value_name;  // empty: a flag
};

// A verb's command line: its usage (printed by --help and after a usage error) and the options
// it accepts. FILE positionals are counted by the verb itself.
struct VerbSpec {
  std::string_view name;
  std::string_view usage;  // the lines after "usage: ncpost "
  std::vector<OptionSpec> options;
};

// The options every verb that reads a program takes.
inline constexpr OptionSpec kSchemasOption{"schemas", "DIR"};
inline constexpr OptionSpec kStrictOption{"strict", ""};
inline constexpr OptionSpec kToolsOption{"tools", "TABLE"};
// G-code input is read with a profile's dialect.json (`trace --dialect`, `post --from`).
inline constexpr OptionSpec kDialectOption{"dialect", "PROFILE"};
inline constexpr OptionSpec kFromOption{"from", "PROFILE"};
inline constexpr OptionSpec kProfilesOption{"profiles", "DIR"};
// The files of DIR are the G-code program's subprogram files (M98 P, CALL PGM, o<name> call).
inline constexpr OptionSpec kSubprogramsOption{"subprograms", "DIR"};

// `--name value`, `--name=value`, flags `--name`, and positionals; `-` alone is a positional.
class Options {
 public:
  Options(Args args, const VerbSpec& spec);

  [[nodiscard]] std::optional<std::string> value(std::string_view name) const;
  [[nodiscard]] bool flag(std::string_view name) const;
  [[nodiscard]] const std::vector<std::string>& positionals() const { return positionals_; }
  [[nodiscard]] bool help() const { return help_; }
  // Non-empty when the command line could not be parsed: a usage error.
  [[nodiscard]] const std::string& error() const { return error_; }

 private:
  std::vector<std::pair<std::string, std::string>> values_;
  std::vector<std::string> flags_;
  std::vector<std::string> positionals_;
  std::string error_;
  bool help_ = false;
};

// The verb's usage on stdout, exit 0.
int print_help(const VerbSpec& spec);
// "ncpost VERB: message" and the verb's usage on stderr, exit 2.
int usage_error(const VerbSpec& spec, std::string_view message);

// Parses the verb's command line. Returns the exit status to end with (after --help, or a usage
// error, or when `files` positionals were not given), nullopt to go on.
[[nodiscard]] std::optional<int> parse_or_exit(const Options& options, const VerbSpec& spec,
                                               std::size_t files = 1);

struct Input {
  std::string name;  // for diagnostics: the path, or "<stdin>"
  std::string bytes;
};

// Reads a path, or stdin for "-". On failure returns nullopt and prints an IO-001 diagnostic.
[[nodiscard]] std::optional<Input> read_input(const std::string& path);

void print_diagnostics(const std::vector<diag::FileDiagnostic>& diagnostics);
// Standard output, piece by piece (unsynchronised with C stdio; flushed by the caller).
void write_stdout(std::string_view piece);

// What a program-reading job needs from the command line: the schemas (--schemas DIR), the
// tool table (--tools TABLE), --strict, this machine's spare cores, and the one FILE.
struct CliJob {
  pipeline::Schemas schemas;
  std::unique_ptr<pipeline::ThreadGroup> threads;
  pipeline::JobContext context;
  pipeline::Input input;
};
// The profiles of --profiles DIR, or the built-in ones.
[[nodiscard]] std::unique_ptr<pipeline::Profiles> open_profiles(const Options& options);
// Null after printing why the job cannot start (a tool table, FILE or --subprograms DIR that
// cannot be read, a G-code dialect profile given by --dialect or --from that does not load).
[[nodiscard]] std::unique_ptr<CliJob> prepare_job(const Options& options);

}  // namespace ncpost::cli
