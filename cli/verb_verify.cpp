// `ncpost verify [--format text|json] [--tolerance MM] [--grid MM] [--tools TABLE]
//                [--schemas DIR] FILE|-`
// Interprets the program as `trace` does and checks each workingstep's motions against the
// feature it claims to machine (docs/verify.md). Text: the report on stdout, diagnostics on
// stderr. JSON: one document on stdout with the diagnostics in it. Exit 0 when every check
// passes, 1 on a failure (or a program that cannot be read or interpreted), 2 on usage.

#include <charconv>
#include <iostream>

#include "cli_support.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::cli {
namespace {

std::optional<double> positive(const std::string& text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v > 0) || v > 1000)
    return std::nullopt;
  return v;
}

}  // namespace

int run_verify(Args args) {
  const Options options(args, {"format", "schemas", "tools", "tolerance", "grid"});
  if (!options.error().empty()) return usage_error("verify", options.error());
  if (options.positionals().size() != 1) return usage_error("verify", "expects one FILE or -");
  const std::string format = options.value("format").value_or("text");
  if (format != "text" && format != "json")
    return usage_error("verify", "--format must be text or json");
  verify::VerifyOptions verify_options;
  if (const auto t = options.value("tolerance")) {
    const auto v = positive(*t);
    if (!v) return usage_error("verify", "--tolerance must be a length in mm, > 0 and <= 1000");
    verify_options.tolerance = *v;
  }
  if (const auto g = options.value("grid")) {
    const auto v = positive(*g);
    if (!v) return usage_error("verify", "--grid must be a length in mm, > 0 and <= 1000");
    verify_options.grid = *v;
  }

  auto job = load_program_job(options);
  if (!job) return kExitRejected;
  verify_options.interpret = job->interpret;
  const stepnc::AttributeReader attributes(job->loaded.model, *job->loaded.schema);
  const verify::VerifyResult result = verify::verify(job->loaded.model, attributes, verify_options);
  print_diagnostics(job->loaded.diagnostics, job->name);
  if (format == "json") {
    std::cout << verify::format_json(result, job->name);
  } else {
    std::cout << verify::format_text(result, job->name);
    print_diagnostics(result.interpreter, job->name);
    for (const auto& f : result.findings)
      std::cerr << diag::format(f.diagnostic, job->name) << '\n';
  }
  std::cout.flush();
  return result.ok() ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
