// Hostile XML: each case is one clean diagnostic, never a crash and never file content.

#include <gtest/gtest.h>

#include "p28_support.hpp"

namespace ncpost::p28 {
namespace {

bool leaks(const p21::ReadResult& r, std::string_view secret) {
  if (r.model.text().find(secret) != std::string_view::npos) return true;
  for (const auto& d : r.diagnostics)
    if (d.message.find(secret) != std::string::npos) return true;
  return false;
}

bool has_code(const p21::ReadResult& r, std::string_view code) {
  for (const auto& d : r.diagnostics)
    if (d.code_id() == code) return true;
  return false;
}

class P28Security : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { initialise_xml(); }
};

TEST_F(P28Security, BillionLaughs) {
  std::string xml = "<?xml version=\"1.0\"?>\n<!DOCTYPE lolz [\n<!ENTITY lol \"lol\">\n";
  xml += "<!ENTITY lol1 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\">\n";
  for (int i = 2; i <= 9; ++i)
    xml += "<!ENTITY lol" + std::to_string(i) + " \"" + [&] {
      std::string s;
      for (int k = 0; k < 10; ++k) s += "&lol" + std::to_string(i - 1) + ";";
      return s;
    }() + "\">\n";
  xml +=
      "]>\n<iso_10303_28 xmlns=\"urn:ncpost:iso10303-28:late-binding\"><data_section>"
      "<entity_instance express_entity_name=\"x\" id=\"Id1\"><attribute_instance "
      "express_attribute_name=\"attr_1\"><string_literal>&lol9;</string_literal>"
      "</attribute_instance></entity_instance></data_section></iso_10303_28>";
  const p21::ReadResult r = read(xml, nullptr);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r, "P28-002")) << test::dump(r.diagnostics);
  EXPECT_LT(r.model.text().size(), 1000u);
}

TEST_F(P28Security, ExternalEntityToEtcPasswd) {
  const std::string xml =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE x [<!ENTITY xxe SYSTEM \"file:///etc/passwd\">]>\n"
      "<iso_10303_28 xmlns=\"urn:ncpost:iso10303-28:late-binding\"><data_section>"
      "<entity_instance express_entity_name=\"x\" id=\"Id1\"><attribute_instance "
      "express_attribute_name=\"attr_1\"><string_literal>&xxe;</string_literal>"
      "</attribute_instance></entity_instance></data_section></iso_10303_28>";
  const p21::ReadResult r = read(xml, nullptr);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r, "P28-002")) << test::dump(r.diagnostics);
  EXPECT_FALSE(leaks(r, "root:"));
}

TEST_F(P28Security, ExternalDtd) {
  const std::string xml =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE x SYSTEM \"file:///etc/passwd\">\n<iso_10303_28/>";
  const p21::ReadResult r = read(xml, nullptr);
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(leaks(r, "root:"));
}

TEST_F(P28Security, DeepNesting) {
  std::string xml =
      "<iso_10303_28 xmlns=\"urn:ncpost:iso10303-28:late-binding\"><data_section>"
      "<entity_instance express_entity_name=\"x\" id=\"Id1\"><attribute_instance "
      "express_attribute_name=\"attr_1\">";
  for (int i = 0; i < 50000; ++i) xml += "<list_literal>";
  const p21::ReadResult r = read(xml, nullptr);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r, "P28-003") || has_code(r, "P28-001")) << test::dump(r.diagnostics);
}

TEST_F(P28Security, SizeLimit) {
  ReadOptions options;
  options.max_bytes = 100;
  const p21::ReadResult r = read(std::string(200, ' '), nullptr, options);
  EXPECT_TRUE(has_code(r, "P28-004"));
}

TEST_F(P28Security, NotXmlAndNotP28) {
  EXPECT_TRUE(has_code(read("ISO-10303-21;", nullptr), "P28-001"));
  EXPECT_TRUE(has_code(read("<html><body/></html>", nullptr), "P28-005"));
  EXPECT_TRUE(
      has_code(read("<iso_10303_28 xmlns=\"urn:ncpost:iso10303-28:late-binding\"><data_section>"
                    "<entity_instance express_entity_name=\"x\" id=\"Id1\">"
                    "<attribute_instance express_attribute_name=\"attr_1\"><real_literal>NaN"
                    "</real_literal></attribute_instance></entity_instance></data_section>"
                    "</iso_10303_28>",
                    nullptr),
               "P28-007"));
}

}  // namespace
}  // namespace ncpost::p28
