// P21 → P28 and P28 → model throughput on one file, with the project's ISO 14649 schema.
//
//   p28_bench FILE.stp [RUNS]     write MB/s (of P21 input) for both bindings, then read MB/s
//                                 of the early-bound XML
//   p28_bench --rss FILE.stp      one read + early-bound write to a null sink; peak RSS

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p28/p28.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: p28_bench FILE.stp [RUNS] | --rss FILE.stp\n";
    return 2;
  }
  ncpost::p28::initialise_xml();
  const auto schema = ncpost::express::parse_express(
      ncpost::bench::slurp(NCPOST_SOURCE_DIR "/schemas/iso14649.exp"));
  const bool rss_mode = std::string(argv[1]) == "--rss";
  const std::string path = rss_mode ? argv[2] : argv[1];
  auto read = ncpost::p21::read(ncpost::bench::slurp(path));
  const double input_mb = static_cast<double>(read.model.text().size()) / 1e6;
  if (rss_mode) {
    std::size_t bytes = 0;
    (void)ncpost::p28::write(read.model, &schema.schemas, ncpost::p28::Binding::Early,
                             [&](std::string_view piece) { bytes += piece.size(); });
    const double rss_mib = ncpost::bench::peak_rss_mib();
    std::cout << "p21_mib=" << input_mb * 1e6 / (1024 * 1024)
              << " xml_mib=" << static_cast<double>(bytes) / (1024 * 1024)
              << " peak_rss_mib=" << rss_mib
              << " rss_over_p21=" << rss_mib / (input_mb * 1e6 / (1024 * 1024)) << '\n';
    return 0;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 3;
  for (auto binding : {ncpost::p28::Binding::Early, ncpost::p28::Binding::Late}) {
    std::vector<double> times;
    std::size_t bytes = 0;
    for (int i = 0; i < runs; ++i) {
      bytes = 0;
      const auto start = std::chrono::steady_clock::now();
      (void)ncpost::p28::write(read.model, &schema.schemas, binding,
                               [&](std::string_view piece) { bytes += piece.size(); });
      times.push_back(seconds_since(start));
    }
    std::sort(times.begin(), times.end());
    std::cout << (binding == ncpost::p28::Binding::Early ? "write_early" : "write_late")
              << " p21_mb=" << input_mb << " xml_mb=" << static_cast<double>(bytes) / 1e6
              << " best_p21_mb_s=" << input_mb / times.front()
              << " median_p21_mb_s=" << input_mb / times[times.size() / 2] << '\n';
  }
  std::string xml;
  (void)ncpost::p28::write(read.model, &schema.schemas, ncpost::p28::Binding::Early,
                           [&](std::string_view piece) { xml += piece; });
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    auto back = ncpost::p28::read(xml, &schema.schemas);
    times.push_back(seconds_since(start));
    if (!back.ok()) std::cerr << "read back with errors\n";
  }
  std::sort(times.begin(), times.end());
  const double xml_mb = static_cast<double>(xml.size()) / 1e6;
  std::cout << "read_early xml_mb=" << xml_mb << " best_xml_mb_s=" << xml_mb / times.front()
            << " median_xml_mb_s=" << xml_mb / times[times.size() / 2] << '\n';
  return 0;
}
