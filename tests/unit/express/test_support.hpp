#pragma once
// Helpers shared by the engine/express tests: parse inline schemas and describe results in a
// form that makes a failing expectation readable.

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "ncpost/express/parse.hpp"

namespace ncpost::express::test {

// "EXP-010@4:3 expected ';' ..." per diagnostic, one per line.
inline std::string describe(const std::vector<diag::Diagnostic>& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics) out += diag::format(d, "") + "\n";
  return out;
}

// "CODE@line:column" for each diagnostic, in order.
inline std::vector<std::string> positions(const ParseResult& result) {
  std::vector<std::string> out;
  for (const auto& d : result.diagnostics)
    out.push_back(std::string(d.code_id()) + "@" + std::to_string(d.line) + ":" +
                  std::to_string(d.column));
  return out;
}

inline std::vector<std::string> codes(const ParseResult& result) {
  std::vector<std::string> out;
  for (const auto& d : result.diagnostics) out.emplace_back(d.code_id());
  return out;
}

inline std::vector<std::string> attribute_names(const Entity& entity) {
  std::vector<std::string> names;
  for (const auto& a : entity.attributes) names.push_back(a.name);
  return names;
}

inline std::vector<std::string> owners(const Entity& entity) {
  std::vector<std::string> names;
  for (const auto& a : entity.attributes) names.push_back(a.owner);
  return names;
}

}  // namespace ncpost::express::test

// Parses `text` into `result` and fails the test (with the diagnostics) if anything was reported.
#define ASSERT_PARSES_CLEANLY(result, text)                                             \
  const ::ncpost::express::ParseResult result = ::ncpost::express::parse_express(text); \
  ASSERT_TRUE(result.diagnostics.empty()) << ::ncpost::express::test::describe(result.diagnostics)
