// Reader throughput and memory on one file.
//
//   p21_read_bench FILE [RUNS] [HELPERS]
//                                  MB/s of read() over RUNS runs (best and median), with
//                                  HELPERS threads lent to read in pieces (default 0: in order)
//   p21_read_bench --rss FILE      one read, then peak RSS and its ratio to the file size
//
// Run the two modes as separate processes: peak RSS is per process.

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/parallel/pieces.hpp"

namespace {}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && std::string(argv[1]) == "--rss") {
    std::string text = ncpost::bench::slurp(argv[2]);
    const double mib = static_cast<double>(text.size()) / (1024.0 * 1024.0);
    auto result = ncpost::p21::read(std::move(text));
    const double rss_mib = ncpost::bench::peak_rss_mib();
    std::cout << "file_mib=" << mib << " instances=" << result.model.instances().size()
              << " errors=" << !result.ok() << " peak_rss_mib=" << rss_mib
              << " rss_over_file=" << rss_mib / mib << '\n';
    return result.ok() ? 0 : 1;
  }
  if (argc < 2) {
    std::cerr << "usage: p21_read_bench FILE [RUNS] [HELPERS] | --rss FILE\n";
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  const ncpost::parallel::ThreadGroup helpers(argc > 3 ? std::stoul(argv[3]) : 0);
  ncpost::p21::ReadOptions options;
  options.helpers = &helpers.helpers();
  std::size_t pieces = 0;
  const std::string original = ncpost::bench::slurp(argv[1]);
  const double mb = static_cast<double>(original.size()) / 1e6;
  std::vector<double> seconds;
  std::size_t instances = 0;
  for (int i = 0; i < runs; ++i) {
    std::string copy = original;  // read() takes ownership; copying is not timed
    const auto start = std::chrono::steady_clock::now();
    auto result = ncpost::p21::read(std::move(copy), options);
    const auto stop = std::chrono::steady_clock::now();
    instances = result.model.instances().size();
    pieces = result.pieces;
    seconds.push_back(std::chrono::duration<double>(stop - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::cout << "file_mb=" << mb << " instances=" << instances << " pieces=" << pieces
            << " runs=" << runs << " best_mb_s=" << mb / seconds.front()
            << " median_mb_s=" << mb / seconds[seconds.size() / 2] << '\n';
  return 0;
}
