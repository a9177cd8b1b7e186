#pragma once
// Shared helpers of the XSLT tests: a fixture that initialises the engine, a temporary profile
// tree (profile/ and common/ folders), and short ways to compile and run stylesheets.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/xslt/xslt.hpp"

namespace ncpost::xslt::test {

// A stylesheet with the usual namespaces around `body` (which starts on line 6), then `output`.
inline std::string sheet(std::string_view body,
                         std::string_view output = R"(<xsl:output method="text"/>)") {
  return std::string(R"(<?xml version="1.0"?>
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:ext="urn:ncpost:ext" xmlns:exsl="http://exslt.org/common"
    xmlns:func="http://exslt.org/functions" xmlns:my="urn:test"
    extension-element-prefixes="exsl func" exclude-result-prefixes="ext my">
)") + std::string(body) +
         "\n" + std::string(output) + "\n</xsl:stylesheet>\n";
}

// A fresh folder tree per test: <tmp>/profile/ and <tmp>/common/, removed afterwards.
class Tree {
 public:
  Tree() {
    static std::atomic<int> counter{0};
    root_ = std::filesystem::temp_directory_path() /
            ("ncpost-xslt-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(root_ / "profile");
    std::filesystem::create_directories(root_ / "common");
    roots_ = {root_ / "profile", root_ / "common"};
  }
  ~Tree() {
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }
  Tree(const Tree&) = delete;
  Tree& operator=(const Tree&) = delete;

  std::filesystem::path write(const std::string& relative, std::string_view text) const {
    const std::filesystem::path p = root_ / relative;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  [[nodiscard]] const std::filesystem::path& root() const { return root_; }
  [[nodiscard]] std::filesystem::path profile() const { return root_ / "profile"; }
  [[nodiscard]] const std::vector<std::filesystem::path>& roots() const { return roots_; }

  CompileResult compile_sheet(std::string_view text, const Limits& limits = {}) const {
    return xslt::compile(write("profile/post.xsl", text), roots_, limits);
  }

 private:
  std::filesystem::path root_;
  std::vector<std::filesystem::path> roots_;
};

class XsltTest : public ::testing::Test {
 protected:
  void SetUp() override { initialise(); }
  Tree tree_;
};

inline std::string all_messages(const std::vector<FileDiagnostic>& diagnostics) {
  std::string out;
  for (const FileDiagnostic& d : diagnostics) out += format(d) + "\n";
  return out;
}

inline bool has_code(const std::vector<FileDiagnostic>& diagnostics, std::string_view code) {
  for (const FileDiagnostic& d : diagnostics) {
    if (d.diagnostic.code_id() == code) return true;
  }
  return false;
}

// Compiles `text` as profile/post.xsl, expecting success.
inline std::shared_ptr<const CompiledStylesheet> compile_ok(const Tree& tree, std::string_view text,
                                                            const Limits& limits = {}) {
  CompileResult r = tree.compile_sheet(text, limits);
  EXPECT_TRUE(r.ok()) << all_messages(r.diagnostics);
  return r.stylesheet;
}

inline constexpr std::string_view kChunk = R"(<chunk seq="1">
  <workingstep id="10" type="MACHINING_WORKINGSTEP" name="WS FINISH PLANAR FACE1">
    <SET_FEED_RATE rate="500"/>
    <STRAIGHT_TRAVERSE x="0" y="0" z="10"/>
    <STRAIGHT_FEED x="91.9" y="-13.5" z="2.5"/>
    <STRAIGHT_FEED x="10" y="2" z="3"/>
    <ARC_FEED x="20" y="2" z="3" cx="15" cy="2" cz="3" ni="0" nj="0" nk="1" turns="-1"
              plane="xy" first_end="20" second_end="2" first_axis="15" second_axis="2"
              rotation="-1" axis_end_point="3"/>
    <COMMENT>finish (face)</COMMENT>
  </workingstep>
</chunk>
)";

}  // namespace ncpost::xslt::test
