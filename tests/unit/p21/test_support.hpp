#pragma once
// Helpers for P21 unit tests: wrap a DATA section into a whole file, and query diagnostics.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "ncpost/p21/reader.hpp"

namespace ncpost::p21::test {

// A minimal, valid file around `data` (placed inside DATA; ... ENDSEC;).
inline std::string wrap(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('t'),'2;1');\n"
         "FILE_NAME('t','2026-01-01T00:00:00',('a'),('o'),'p','s','z');\n"
         "FILE_SCHEMA(('TEST_SCHEMA'));\nENDSEC;\nDATA;\n" +
         data + "\nENDSEC;\nEND-ISO-10303-21;\n";
}
// The line on which `data` starts inside wrap().
inline constexpr std::uint32_t kFirstDataLine = 8;

inline std::vector<std::string> codes(const ReadResult& r) {
  std::vector<std::string> out;
  for (const auto& d : r.diagnostics) out.emplace_back(d.code_id());
  return out;
}

inline std::string dump(const ReadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics) out += diag::format(d, "f") + "\n";
  return out;
}

inline const diag::Diagnostic* find_code(const ReadResult& r, std::string_view code) {
  auto it = std::find_if(r.diagnostics.begin(), r.diagnostics.end(),
                         [&](const auto& d) { return d.code_id() == code; });
  return it == r.diagnostics.end() ? nullptr : &*it;
}

}  // namespace ncpost::p21::test
