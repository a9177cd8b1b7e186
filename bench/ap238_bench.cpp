// The AP238 AIM interpreter against the ISO 14649 one on the same motions: the two files
// make_ap238_program writes, each read once and interpreted RUNS times into a sink that counts
// the calls. Prints, per form, the file size, reading time, interpretation time (best and
// median; the AIM's includes building its index of links), motions per second, and the ratio
// of the AIM's speed to the ARM's (issue 18's target: at least 0.5), and checks that both gave
// the same motions.
//
//   ap238_bench ARM.stp AIM.stp [RUNS]
//   ap238_bench - AIM.stp [RUNS]     the AIM file alone (for a profiler)

#include <algorithm>
#include <chrono>
#include <iostream>
#include <string_view>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/ap238/ap238.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace {

// Counts motions and folds their end points into a checksum, so that both forms can be
// compared without keeping the calls.
class MotionCount final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call& c) override {
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, ncpost::canon::StraightTraverse> ||
                        std::is_same_v<T, ncpost::canon::StraightFeed>) {
            add(v.to.x + 3 * v.to.y + 7 * v.to.z);
          } else if constexpr (std::is_same_v<T, ncpost::canon::ArcFeed>) {
            add(v.end.x + 3 * v.end.y + 7 * v.end.z + 11 * v.centre.x + 13 * v.turns);
          }
        },
        c);
  }
  void add(double v) {
    ++motions;
    checksum += v * static_cast<double>(motions % 97 + 1);
  }
  std::size_t motions = 0;
  double checksum = 0;
};

struct Measured {
  double mb = 0;
  double read_s = 0;
  double best_s = 0;
  double median_s = 0;
  std::size_t motions = 0;
  double checksum = 0;
  bool ok = true;
};

Measured measure(const char* path, int runs, bool aim) {
  Measured m;
  std::string text = ncpost::bench::slurp(path);
  m.mb = static_cast<double>(text.size()) / 1e6;
  const auto read_start = std::chrono::steady_clock::now();
  auto read = ncpost::p21::read(std::move(text));
  m.read_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
  const ncpost::express::SchemaRegistry registry;
  const auto selection = registry.select_or_builtin(read.model);
  const ncpost::stepnc::AttributeReader attributes(read.model, *selection.set());
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    MotionCount sink;
    const auto start = std::chrono::steady_clock::now();
    const auto result = aim ? ncpost::ap238::interpret(read.model, attributes, sink)
                            : ncpost::stepnc::interpret(read.model, attributes, sink);
    times.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m.motions = sink.motions;
    m.checksum = sink.checksum;
    m.ok = result.ok();
  }
  std::sort(times.begin(), times.end());
  m.best_s = times.front();
  m.median_s = times[times.size() / 2];
  return m;
}

void print(const char* form, const Measured& m) {
  std::cout << form << ": file_mb=" << m.mb << " read_s=" << m.read_s
            << " interpret_best_s=" << m.best_s << " interpret_median_s=" << m.median_s
            << " motions=" << m.motions
            << " motions_per_s=" << static_cast<double>(m.motions) / m.median_s
            << " ok=" << (m.ok ? "yes" : "no") << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: ap238_bench ARM.stp AIM.stp [RUNS]\n";
    return 2;
  }
  const int runs = argc > 3 ? std::max(1, std::stoi(argv[3])) : 3;
  if (std::string_view(argv[1]) == "-") {
    print("aim", measure(argv[2], runs, true));
    return 0;
  }
  const Measured arm = measure(argv[1], runs, false);
  print("arm", arm);
  const Measured aim = measure(argv[2], runs, true);
  print("aim", aim);
  const bool same = arm.motions == aim.motions && arm.checksum == aim.checksum;
  const double ratio = (static_cast<double>(aim.motions) / aim.median_s) /
                       (static_cast<double>(arm.motions) / arm.median_s);
  std::cout << "same_motions=" << (same ? "yes" : "no") << " aim_speed_over_arm=" << ratio
            << " peak_rss_mib=" << ncpost::bench::peak_rss_mib() << '\n';
  return same && arm.ok && aim.ok ? 0 : 1;
}
