// G-code in (engine/gcode): read + evaluate + convert a program into a sink that counts the
// canonical calls, with throughput and peak RSS; a generated program of any size; a FANUC
// macro B loop of N iterations. bench/gcode_run.sh runs them side by side with /usr/bin/rs274.
//
//   gcode_bench read FILE [DIALECT_ID] [RUNS]   (dialect: stylesheets/<id>/dialect.json, linuxcnc)
//   gcode_bench generate MB OUT                 (a LinuxCNC program rs274 reads too)
//   gcode_bench macro-loop N [RUNS]             (#1 counted to N in a WHILE loop, fanuc-0i)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace {

class CountingSink final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call&) override { ++calls; }
  std::size_t calls = 0;
};

std::shared_ptr<const ncpost::gcode::Dialect> dialect(const std::string& id) {
  const std::string path = std::string(NCPOST_SOURCE_DIR) + "/stylesheets/" + id + "/dialect.json";
  auto loaded = ncpost::gcode::load_dialect(ncpost::bench::slurp(path));
  if (!loaded.dialect) {
    std::cerr << path << ": not a valid dialect\n";
    std::exit(2);
  }
  return loaded.dialect;
}

// Reads `text` `runs` times; prints the best and median time, MB/s and the peak RSS.
int time_reads(const std::string& label, const std::string& text, const std::string& id, int runs,
               double rss_before) {
  const auto d = dialect(id);
  std::vector<double> times;
  std::vector<double> cpu_times;  // the shared machine's load inflates wall time, not CPU time
  std::size_t calls = 0;
  std::size_t diagnostics = 0;
  for (int i = 0; i < runs; ++i) {
    CountingSink sink;
    ncpost::gcode::ReadOptions options;
    options.program_name = label;
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    const auto r = ncpost::gcode::read(text, *d, sink, options);
    times.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    cpu_times.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    calls = sink.calls;
    diagnostics = r.diagnostics.size();
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu_times.begin(), cpu_times.end());
  const double mb = static_cast<double>(text.size()) / 1e6;
  std::printf(
      "%s (%s): %.1f MB, %zu calls, %zu diagnostics; wall best %.3f s (%.0f MB/s), median %.3f "
      "s; CPU best %.3f s (%.0f MB/s); peak RSS %.1f MiB with the text loaded, %.1f MiB after "
      "reading\n",
      label.c_str(), id.c_str(), mb, calls, diagnostics, times.front(), mb / times.front(),
      times[times.size() / 2], cpu_times.front(), mb / cpu_times.front(), rss_before,
      ncpost::bench::peak_rss_mib());
  return 0;
}

int generate(double megabytes, const std::string& out_path) {
  std::ofstream out(out_path, std::ios::binary);
  out << "(ncpost gcode_bench: a generated milling program)\n"
         "G21 G17 G90 G94 G40 G49 G80\nS10000 M3\nF1200\nG0 X0 Y0 Z5\n";
  const auto target = static_cast<std::size_t>(megabytes * 1e6);
  std::size_t written = 0;
  char line[160];
  for (std::size_t k = 0; written < target; ++k) {
    const double x = static_cast<double>(k % 1000) * 0.25;
    const double y = static_cast<double>((k / 1000) % 1000) * 0.25;
    const double r = 0.5 + static_cast<double>(k % 7) * 0.125;
    int n = 0;
    if (k % 50 == 0) n += std::snprintf(line + n, sizeof line - n, "(pass %zu)\n", k);
    n += std::snprintf(line + n, sizeof line - n,
                       "N%zu G1 X%.4f Y%.4f Z-1.0000\nG2 X%.4f Y%.4f I%.4f J0\nG0 Z5\n", k % 100000,
                       x, y, x + 2 * r, y, r);
    out.write(line, n);
    written += static_cast<std::size_t>(n);
  }
  out << "M5\nM2\n";
  return out ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "read" && argc >= 3) {
    const std::string text = ncpost::bench::slurp(argv[2]);
    const double rss = ncpost::bench::peak_rss_mib();
    return time_reads(argv[2], text, argc > 3 ? argv[3] : "linuxcnc",
                      argc > 4 ? std::stoi(argv[4]) : 3, rss);
  }
  if (mode == "generate" && argc == 4) return generate(std::stod(argv[2]), argv[3]);
  if (mode == "macro-loop" && argc >= 3) {
    const std::string n = argv[2];
    const std::string text = "%\nO0001\n#1=0\n#2=0\nWHILE [#1 LT " + n +
                             "] DO1\n#2=#2+[#1 MOD 7]*0.5\n#1=#1+1\nEND1\nG0 X[#2/" + n +
                             "]\nM30\n%\n";
    return time_reads("macro loop of " + n + " iterations", text, "fanuc-0i",
                      argc > 3 ? std::stoi(argv[3]) : 3, ncpost::bench::peak_rss_mib());
  }
  std::cerr << "usage: gcode_bench read FILE [DIALECT_ID] [RUNS] | generate MB OUT | "
               "macro-loop N [RUNS]\n";
  return 2;
}
