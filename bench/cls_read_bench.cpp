// The CL reader's speed and memory (issue 20: ≥ 100 MB/s, memory not growing with the file).
//   cls_read_bench FILE [RUNS] [CHECKS_JSON]   MB/s best and median: the whole file in memory read
//                                              at once, and the file streamed in 1 MB pieces
//                                              (Reader::feed), into a sink that counts calls
//   cls_read_bench --rss FILE [CHECKS_JSON]    streams the file in 1 MB pieces and prints the
//                                              peak RSS: run it on files of different sizes
// With CHECKS_JSON (a `checks` section) the shop's checks run too.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "ncpost/cls/checks.hpp"
#include "ncpost/cls/reader.hpp"

namespace {

class CountingSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call& c) override {
    ++calls;
    motions += ncpost::canon::is_motion(c) ? 1 : 0;
  }
  std::size_t calls = 0;
  std::size_t motions = 0;
};

std::string read_file(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

ncpost::cls::ReadResult stream(const char* path, ncpost::canon::Sink& sink,
                               const ncpost::cls::ReadOptions& options, std::size_t& bytes) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buffer(std::size_t{1} << 20);
  ncpost::cls::Reader reader(sink, options);
  bytes = 0;
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    bytes += n;
    reader.feed(std::string_view(buffer.data(), n));
  }
  return reader.finish();
}

std::optional<ncpost::cls::CheckConfig> checks_from(const char* path) {
  if (!path) return std::nullopt;
  std::vector<ncpost::diag::Diagnostic> d;
  auto config = ncpost::cls::parse_checks(std::string_view(read_file(path)), d);
  if (!config) std::fprintf(stderr, "%s: not a valid checks section\n", path);
  return config;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && std::string(argv[1]) == "--rss") {
    const auto checks = checks_from(argc > 3 ? argv[3] : nullptr);
    ncpost::cls::ReadOptions options;
    if (checks) options.checks = &*checks;
    const long before = peak_rss_kb();
    CountingSink sink;
    std::size_t bytes = 0;
    const auto r = stream(argv[2], sink, options, bytes);
    std::printf(
        "%s: %.1f MB streamed, %zu calls, %zu diagnostics; peak RSS %ld kB (%ld kB "
        "before reading)\n",
        argv[2], static_cast<double>(bytes) / 1e6, sink.calls, r.diagnostics.size(), peak_rss_kb(),
        before);
    return r.ok() ? 0 : 1;
  }
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: cls_read_bench FILE [RUNS] [CHECKS_JSON] | --rss FILE [CHECKS_JSON]\n");
    return 2;
  }
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  const auto checks = checks_from(argc > 3 ? argv[3] : nullptr);
  ncpost::cls::ReadOptions options;
  if (checks) options.checks = &*checks;
  const std::string text = read_file(argv[1]);
  const double mb = static_cast<double>(text.size()) / 1e6;
  std::vector<double> whole, streamed;
  std::size_t calls = 0, motions = 0;
  bool ok = true;
  for (int i = 0; i < runs; ++i) {
    CountingSink sink;
    auto t0 = std::chrono::steady_clock::now();
    const auto r = ncpost::cls::read(text, sink, options);
    auto t1 = std::chrono::steady_clock::now();
    whole.push_back(mb / std::chrono::duration<double>(t1 - t0).count());
    ok = ok && r.ok();
    calls = sink.calls;
    motions = sink.motions;
    CountingSink sink2;
    std::size_t bytes = 0;
    t0 = std::chrono::steady_clock::now();
    (void)stream(argv[1], sink2, options, bytes);
    t1 = std::chrono::steady_clock::now();
    streamed.push_back(mb / std::chrono::duration<double>(t1 - t0).count());
  }
  std::sort(whole.begin(), whole.end());
  std::sort(streamed.begin(), streamed.end());
  std::printf("%s: %.1f MB, %zu calls (%zu motions)%s%s\n", argv[1], mb, calls, motions,
              checks ? ", checks on" : "", ok ? "" : ", WITH ERRORS");
  std::printf("  in memory: best %.0f MB/s, median %.0f MB/s\n", whole.back(),
              whole[whole.size() / 2]);
  std::printf("  streamed in 1 MB pieces (file read included): best %.0f MB/s, median %.0f MB/s\n",
              streamed.back(), streamed[streamed.size() / 2]);
  return ok ? 0 : 1;
}
