// Toolpath generation from features (docs/features.md) on a program from make_feature_program:
// interpretation time with every motion generated, workingsteps and canonical calls per second,
// and the time of each pocket and hole workingstep (from its WORKINGSTEP_BEGIN to its END, so
// generation and emission both count).
//
//   feature_bench FILE [RUNS]

#include <algorithm>
#include <chrono>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Times each workingstep by its markers and drops the calls.
class TimingSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call& c) override {
    ++calls;
    if (const auto* b = std::get_if<ncpost::canon::Begin>(&c);
        b && b->scope == ncpost::canon::Scope::Workingstep) {
      pocket_ = b->entity.name.rfind("POCKET", 0) == 0;
      start_ = Clock::now();
      ++workingsteps;
    } else if (const auto* e = std::get_if<ncpost::canon::End>(&c);
               e && e->scope == ncpost::canon::Scope::Workingstep) {
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
      (pocket_ ? pockets : holes).push_back(ms);
    }
  }
  void reset() {
    calls = 0;
    workingsteps = 0;
    pockets.clear();
    holes.clear();
  }
  std::size_t calls = 0;
  std::size_t workingsteps = 0;
  std::vector<double> pockets;
  std::vector<double> holes;

 private:
  Clock::time_point start_{};
  bool pocket_ = false;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: feature_bench FILE [RUNS]\n";
    return 2;
  }
  const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 3;
  auto read = ncpost::p21::read(ncpost::bench::slurp(argv[1]));
  const ncpost::express::SchemaRegistry registry;
  const auto selection = registry.select_or_builtin(read.model);
  const ncpost::stepnc::AttributeReader attributes(read.model, *selection.set());
  std::vector<double> times;
  TimingSink sink;
  for (int i = 0; i < runs; ++i) {
    sink.reset();
    const auto start = Clock::now();
    const auto result = ncpost::stepnc::interpret(read.model, attributes, sink);
    times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    if (!result.ok()) {
      std::cerr << "interpreted with errors:\n";
      for (const auto& d : result.diagnostics) std::cerr << "  " << d.message << '\n';
      return 1;
    }
  }
  std::sort(times.begin(), times.end());
  const double t = times[times.size() / 2];
  std::cout << "workingsteps=" << sink.workingsteps << " calls=" << sink.calls
            << " interpret_median_s=" << t << " interpret_best_s=" << times.front()
            << " workingsteps_per_s=" << static_cast<double>(sink.workingsteps) / t
            << " calls_per_s=" << static_cast<double>(sink.calls) / t
            << " pocket_median_ms=" << median(sink.pockets) << " pocket_max_ms="
            << (sink.pockets.empty() ? 0
                                     : *std::max_element(sink.pockets.begin(), sink.pockets.end()))
            << " pocket_mean_ms="
            << (sink.pockets.empty()
                    ? 0
                    : std::accumulate(sink.pockets.begin(), sink.pockets.end(), 0.0) /
                          static_cast<double>(sink.pockets.size()))
            << " pocket_sum_ms=" << std::accumulate(sink.pockets.begin(), sink.pockets.end(), 0.0)
            << " pockets=" << sink.pockets.size() << " hole_median_ms=" << median(sink.holes)
            << " hole_sum_ms=" << std::accumulate(sink.holes.begin(), sink.holes.end(), 0.0)
            << " peak_rss_mib=" << ncpost::bench::peak_rss_mib() << '\n';
  return 0;
}
