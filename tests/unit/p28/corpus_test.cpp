// The ISO 10303-28 edition 2 documents of the corpus (ifcXML, written by other tools), read
// without their schema (IFC2X3/IFC4 are not shipped): every instance of the P21 twin comes back
// with its id and entity, and with the same values in the same order where the twin has values.
// Attribute positions themselves need the schema, so unset ($) positions are not compared.

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <set>

#include "ncpost/p21/writer.hpp"
#include "p28_support.hpp"

namespace ncpost::p28 {
namespace {

// The leaf values of an instance in order, skipping $, as comparable text.
void leaves(const p21::Model& m, p21::Value v, std::vector<std::string>& out) {
  using p21::ValueKind;
  switch (v.kind()) {
    case ValueKind::Omitted:
    case ValueKind::Derived:
      return;
    case ValueKind::List:
      for (p21::Value item : m.items(v)) leaves(m, item, out);
      return;
    case ValueKind::Typed:
      leaves(m, m.typed_child(v), out);
      return;
    case ValueKind::Reference:
      out.push_back("#" + std::to_string(v.id()));
      return;
    case ValueKind::Integer:
    case ValueKind::Real:
      out.push_back(std::to_string(m.as_real(v) + 0.0));
      return;  // -0 is 0
    case ValueKind::String: {
      // Without the schema a string of digits reads back as a number, and an enumeration as
      // a string: compare numbers as numbers and text without case.
      std::string s = m.as_string(v);
      std::transform(s.begin(), s.end(), s.begin(),
                     [](unsigned char c) { return std::toupper(c); });
      double d = 0;
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), d);
      out.push_back(
          ec == std::errc() && end == s.data() + s.size() && !s.empty() ? std::to_string(d) : s);
      return;
    }
    default: {
      std::string s(m.slice(v));
      std::transform(s.begin(), s.end(), s.begin(),
                     [](unsigned char c) { return std::toupper(c); });
      // Booleans: .T. in P21, "true" in ifcXML (a string without the schema).
      if (s == "T") s = "TRUE";
      if (s == "F") s = "FALSE";
      if (s == "U") s = "UNKNOWN";
      out.push_back(s);
    }
  }
}

std::string upper(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  return out;
}

struct TwinCase {
  const char* xml;
  const char* twin;
};
void PrintTo(const TwinCase& c, std::ostream* os) {
  *os << c.xml;
}

class P28Corpus : public ::testing::TestWithParam<TwinCase> {};

TEST_P(P28Corpus, ReadsLikeItsP21Twin) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const p21::ReadResult twin = p21::read(ncpost::test::read_file(corpus / GetParam().twin));
  ASSERT_TRUE(twin.ok());
  const p21::ReadResult r = read(ncpost::test::read_file(corpus / GetParam().xml), nullptr);
  ASSERT_TRUE(r.ok()) << test::dump(r.diagnostics);
  std::size_t compared = 0;
  for (const p21::Instance& t : twin.model.instances()) {
    const p21::Instance* x = r.model.find(t.id);
    ASSERT_NE(x, nullptr) << "#" << t.id << " missing";
    ASSERT_EQ(upper(r.model.type_name(*x)), upper(twin.model.type_name(t))) << "#" << t.id;
    std::vector<std::string> a;
    std::vector<std::string> b;
    for (p21::Value v : twin.model.params(t)) leaves(twin.model, v, a);
    for (p21::Value v : r.model.params(*x)) leaves(r.model, v, b);
    // ifcXML leaves out derived and inverse data and some defaults, so the XML's values must
    // appear in the twin's, in order.
    std::size_t j = 0;
    for (const std::string& value : b) {
      while (j < a.size() && a[j] != value) ++j;
      ASSERT_LT(j, a.size()) << "#" << t.id << " value '" << value << "' is not in the twin";
      ++j;
    }
    ++compared;
  }
  EXPECT_EQ(compared, twin.model.instances().size());
}

INSTANTIATE_TEST_SUITE_P(Ifc, P28Corpus,
                         ::testing::Values(TwinCase{"p28/xbim_4walls1floorSite.ifcxml",
                                                    "p28/xbim_4walls1floorSite_P21_twin.ifc"}));

// Allplan's ifcXML numbers its instances differently from its P21 twin and leaves some out, so
// the comparison is by entity type: no type appears more often in the XML than in the twin,
// and the XML holds most of the twin's instances.
TEST(P28CorpusRenumbered, AllplanHasTheTwinsEntities) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const p21::ReadResult twin =
      p21::read(ncpost::test::read_file(corpus / "p28/steputils_allplan_test-01_P21_twin.ifc"));
  const p21::ReadResult r =
      read(ncpost::test::read_file(corpus / "p28/steputils_allplan_test-01.ifcXML"), nullptr);
  ASSERT_TRUE(r.ok()) << test::dump(r.diagnostics);
  std::map<std::string, std::size_t> in_twin;
  std::map<std::string, std::size_t> in_xml;
  for (const auto& i : twin.model.instances()) ++in_twin[upper(twin.model.type_name(i))];
  for (const auto& i : r.model.instances()) ++in_xml[upper(r.model.type_name(i))];
  for (const auto& [type, n] : in_xml) EXPECT_LE(n, in_twin[type]) << type;
  EXPECT_GT(r.model.instances().size(), twin.model.instances().size() * 9 / 10);
  // Ed.2 writes a SELECT member of a defined simple type as `<IfcText-wrapper>`: the value is
  // typed IFCTEXT as in the twin, not IFCTEXT-WRAPPER (which P21 cannot read back).
  const std::string written = p21::write_to_string(r.model);
  EXPECT_NE(written.find("IFCTEXT('aktiv')"), std::string::npos);
  EXPECT_NE(written.find("IFCNORMALISEDRATIOMEASURE("), std::string::npos);
  EXPECT_EQ(written.find("-WRAPPER"), std::string::npos);
  EXPECT_TRUE(p21::read(written).ok());
}

TEST(P28CorpusOthers, EveryDocumentReadsOrGivesItsExpectedError) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const std::set<std::string> ed2_documents = {
      "xbim_4walls1floorSite.ifcxml", "steputils_allplan_test-01.ifcXML", "xbim_InvalidNan.ifcxml"};
  for (const auto& entry : std::filesystem::directory_iterator(corpus / "p28")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".ifcxml" && ext != ".ifcXML") continue;
    const p21::ReadResult r = read(ncpost::test::read_file(entry.path()), nullptr);
    const std::string name = entry.path().filename().string();
    if (name == "xbim_InvalidNan.ifcxml") {  // <TargetScale>NAN(SNAN)</TargetScale>
      ASSERT_FALSE(r.ok()) << name;
      EXPECT_EQ(r.diagnostics[0].code_id(), "P28-007") << test::dump(r.diagnostics);
      continue;
    }
    if (!ed2_documents.count(name)) {  // ifcXML 4: a clear "not supported"
      ASSERT_FALSE(r.ok()) << name;
      EXPECT_EQ(r.diagnostics[0].code_id(), "P28-011") << test::dump(r.diagnostics);
      continue;
    }
    EXPECT_TRUE(r.ok()) << name << "\n" << test::dump(r.diagnostics);
    EXPECT_GT(r.model.instances().size(), 0u) << name;
  }
}

}  // namespace
}  // namespace ncpost::p28
