// ncpostd: the HTTP service. Parses the command line, sets up libxml2/libxslt on the main
// thread (they must be initialised before any worker parses XML), opens the profile store and
// runs the server until SIGTERM. docs/server.md describes the routes, limits and logs.

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <boost/system/system_error.hpp>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "auth.hpp"
#include "config.hpp"
#include "ncpost/pipeline/process.hpp"
#include "ncpost/pipeline/profiles.hpp"
#include "server.hpp"

int main(int argc, char** argv) {
  using namespace ncpost;
  std::vector<std::string_view> args(argv + 1, argv + argc);
  const server::ParsedArgs parsed = server::parse_args(args);
  if (parsed.help) {
    std::cout << server::usage();
    return 0;
  }
  if (!parsed.config) {
    std::cerr << "ncpostd: " << parsed.error << "\n" << server::usage();
    return 2;
  }
  const server::Config config = server::resolve_threads(*parsed.config);

  // One JSON object per line on stderr: the start-up line (with "listening"), access lines,
  // signals. Machine-readable, so the port can be taken from it.
  auto log = spdlog::stderr_logger_mt("ncpostd");
  log->set_pattern("%v");
  log->flush_on(spdlog::level::info);
  const auto fail = [&](const std::string& message) {
    nlohmann::json line;
    line["event"] = "error";
    line["message"] = message;
    log->error(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    return 1;
  };

  pipeline::initialise_process();

  std::vector<std::string> token_errors;
  std::vector<std::string> token_warnings;
  std::optional<std::string> token =
      server::load_admin_token(config.admin_token_file, token_errors, token_warnings);
  if (!token_errors.empty()) {
    for (const auto& e : token_errors) fail(e);
    return 2;
  }
  for (const auto& w : token_warnings) {
    nlohmann::json line;
    line["event"] = "warning";
    line["message"] = w;
    log->warn(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }

  std::unique_ptr<pipeline::Profiles> profiles;
  try {
    profiles = config.profiles ? pipeline::Profiles::writable_over_builtins(*config.profiles)
                               : std::make_unique<pipeline::Profiles>();
  } catch (const std::exception& e) {
    return fail(std::string("cannot open the profile directory: ") + e.what());
  }
  profiles->hide_server_paths();

  try {
    server::Server server(config, *profiles, std::move(token), log);
    return server.run();
  } catch (const boost::system::system_error& e) {
    return fail("cannot listen on " + config.host + ":" + std::to_string(config.port) + ": " +
                e.what());
  }
}
