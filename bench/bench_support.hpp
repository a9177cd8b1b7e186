#pragma once
// What every benchmark program needs: a file in memory, and this process's peak RSS.

#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace ncpost::bench {

// A benchmark cannot go on without its input: an unreadable file ends the program (exit 2).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (!in || size < 0) {
    std::cerr << path << ": cannot be read\n";
    std::exit(2);
  }
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  return text;
}

inline double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace ncpost::bench
