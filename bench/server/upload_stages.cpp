// upload_stages FILE PROFILE [RUNS] [HELPERS]: the work a POST /v1/posts does after the last
// body byte arrived, stage by stage, for one program (bench/server/run.sh runs it on the ~100 MB
// file): the upload copy, the whole-input hash, P21 read, schema selection and check, then
// interpretation and rendering up to the first piece of controller text. Median ms per stage.
// HELPERS (default 1: a two-worker ncpostd with one worker free) threads are lent to the read
// and the check, as ncpostd lends its idle workers; 0 reads and checks in order.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "../bench_support.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: upload_stages FILE PROFILE [RUNS] [HELPERS]\n";
    return 2;
  }
  const int runs = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  const ncpost::parallel::ThreadGroup helpers(argc > 4 ? std::stoul(argv[4]) : 1);
  ncpost::xslt::initialise();
  ncpost::profile::ProfileStore store;
  std::vector<ncpost::diag::FileDiagnostic> profile_diagnostics;
  const auto profile = store.load(argv[2], profile_diagnostics);
  if (!profile) {
    std::cerr << "profile " << argv[2] << " does not load\n";
    return 1;
  }
  const ncpost::express::SchemaRegistry registry;
  const std::string file = ncpost::bench::slurp(argv[1]);
  std::vector<double> copy, hash, read, check, first;
  volatile std::size_t sink = 0;
  for (int i = 0; i < runs; ++i) {
    auto t = Clock::now();
    std::string bytes = file;  // what a multipart upload costs: the part copied out
    copy.push_back(ms_since(t));
    t = Clock::now();
    sink = sink + std::hash<std::string_view>{}(bytes);
    hash.push_back(ms_since(t));
    t = Clock::now();
    ncpost::p21::ReadOptions read_options;
    read_options.helpers = &helpers.helpers();
    auto result = ncpost::p21::read(std::move(bytes), read_options);
    read.push_back(ms_since(t));
    t = Clock::now();
    ncpost::pipeline::LoadedModel loaded;
    loaded.model = std::move(result.model);
    auto selection = registry.select_or_builtin(loaded.model);
    loaded.schema = selection.set();
    ncpost::express::ValidateOptions validate_options;
    validate_options.helpers = &helpers.helpers();
    auto checked = ncpost::express::validate(loaded.model, *loaded.schema, validate_options);
    check.push_back(ms_since(t));
    if (!checked.empty()) std::cerr << checked.size() << " schema diagnostics\n";
    t = Clock::now();
    // The first piece cancels the job: the rest of the post is not what this measures.
    std::atomic<bool> stop{false};
    ncpost::pipeline::PostOptions options;
    options.cancel = &stop;
    options.render_thread_min_instances = 0;  // as ncpostd runs a post: one thread per job
    double first_ms = -1;
    (void)ncpost::pipeline::post(
        loaded, *profile,
        [&](std::string_view) {
          if (first_ms < 0) first_ms = ms_since(t);
          stop = true;
        },
        options);
    first.push_back(first_ms);
  }
  std::cout << "file_mb=" << static_cast<double>(file.size()) / 1e6 << " runs=" << runs
            << " copy_ms=" << median(copy) << " hash_ms=" << median(hash)
            << " read_ms=" << median(read) << " check_ms=" << median(check)
            << " first_text_ms=" << median(first) << '\n';
  return 0;
}
