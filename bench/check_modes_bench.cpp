// The schema check, strict against tolerant, on one file (issue 17: the tolerant mode may cost
// at most 5%). The modes alternate run by run in one process, so that both see the same machine.
//
//   check_modes_bench FILE [RUNS]   seconds of express::validate per mode (median and best of
//                                   RUNS, default 5), and the tolerant median over the strict;
//                                   then the same for the interpretation into a counting sink
//                                   (stepnc::Mode: the variants table, implicit values and the
//                                   units cross-check are the tolerant reading's extra work)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace {

class CountingSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call&) override { ++calls; }
  std::size_t calls = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: check_modes_bench FILE [RUNS]\n";
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  const auto read = ncpost::p21::read(ncpost::bench::slurp(argv[1]));
  const ncpost::express::SchemaRegistry registry;
  const auto selection = registry.select_or_builtin(read.model);
  const ncpost::express::CheckPlan plan(*selection.set());
  std::vector<double> seconds[2];
  std::size_t diagnostics[2] = {0, 0};
  for (int run = 0; run < runs; ++run)
    for (const bool tolerant : {false, true}) {
      ncpost::express::ValidateOptions options;
      options.plan = &plan;
      options.tolerant = tolerant;
      const auto started = std::chrono::steady_clock::now();
      diagnostics[tolerant] =
          ncpost::express::validate(read.model, *selection.set(), options).size();
      seconds[tolerant].push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }
  for (const bool tolerant : {false, true})
    std::printf("%-8s median %.3f s, best %.3f s, %zu diagnostics\n",
                tolerant ? "tolerant" : "strict", median(seconds[tolerant]),
                *std::min_element(seconds[tolerant].begin(), seconds[tolerant].end()),
                diagnostics[tolerant]);
  std::printf("tolerant / strict (medians): %.3f\n", median(seconds[1]) / median(seconds[0]));
  std::vector<double> interpret[2];
  std::size_t calls[2] = {0, 0};
  for (int run = 0; run < runs; ++run)
    for (const bool tolerant : {false, true}) {
      const auto mode = tolerant ? ncpost::stepnc::Mode::Tolerant : ncpost::stepnc::Mode::Strict;
      const auto started = std::chrono::steady_clock::now();
      const ncpost::stepnc::AttributeReader attributes(read.model, *selection.set(), mode);
      CountingSink sink;
      (void)ncpost::stepnc::interpret(read.model, attributes, sink);
      interpret[tolerant].push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
      calls[tolerant] = sink.calls;
    }
  for (const bool tolerant : {false, true})
    std::printf("interpret %-8s median %.3f s, best %.3f s, %zu calls\n",
                tolerant ? "tolerant" : "strict", median(interpret[tolerant]),
                *std::min_element(interpret[tolerant].begin(), interpret[tolerant].end()),
                calls[tolerant]);
  std::printf("interpret tolerant / strict (medians): %.3f\n",
              median(interpret[1]) / median(interpret[0]));
  return 0;
}
