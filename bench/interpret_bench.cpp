// The interpreter on one file: reading time, interpreting time (canonical calls streamed as
// chunks to a sink that drops them), calls per second, and peak RSS after each step.
//
//   interpret_bench FILE [RUNS]

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace {

class DropChunks final : public ncpost::canon::ChunkSink {
 public:
  void chunk(const ncpost::canon::ChunkView& c) override {
    ++chunks;
    largest = std::max(largest, c.calls.size());
  }
  std::size_t chunks = 0;
  std::size_t largest = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: interpret_bench FILE [RUNS]\n";
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 3;
  std::string text = ncpost::bench::slurp(argv[1]);
  const double mb = static_cast<double>(text.size()) / 1e6;
  const auto read_start = std::chrono::steady_clock::now();
  auto read = ncpost::p21::read(std::move(text));
  const double read_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
  const double rss_after_read = ncpost::bench::peak_rss_mib();
  const ncpost::express::SchemaRegistry registry;
  const auto selection = registry.select_or_builtin(read.model);
  const ncpost::stepnc::AttributeReader attributes(read.model, *selection.set());
  std::vector<double> times;
  std::size_t calls = 0;
  DropChunks sink;
  for (int i = 0; i < runs; ++i) {
    sink.chunks = 0;
    sink.largest = 0;
    ncpost::canon::Chunker chunker(sink);
    const auto start = std::chrono::steady_clock::now();
    const auto result = ncpost::stepnc::interpret(read.model, attributes, chunker);
    chunker.finish();
    times.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    calls = result.calls;
    if (!result.ok()) std::cerr << "interpreted with errors\n";
  }
  std::sort(times.begin(), times.end());
  std::cout << "file_mb=" << mb << " read_s=" << read_s << " interpret_best_s=" << times.front()
            << " interpret_median_s=" << times[times.size() / 2]
            << " interpret_over_read=" << times[times.size() / 2] / read_s << " calls=" << calls
            << " calls_per_s=" << static_cast<double>(calls) / times[times.size() / 2]
            << " chunks=" << sink.chunks << " largest_chunk_calls=" << sink.largest
            << " peak_rss_after_read_mib=" << rss_after_read
            << " peak_rss_after_interpret_mib=" << ncpost::bench::peak_rss_mib() << '\n';
  return 0;
}
