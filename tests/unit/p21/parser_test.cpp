// The reader on well-formed input: sections, instances, values and indexes.

#include <gtest/gtest.h>

#include "ncpost/p21/reader.hpp"
#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

using test::codes;
using test::dump;
using test::wrap;

TEST(Reader, SimpleInstancesAndValues) {
  const auto r =
      read(wrap("#1=CARTESIAN_POINT('p',(1.5,-2.,3.E1));\n"
                "#2=THING($,*,42,.T.,\"1F\",#1,(),((1,2),(3)),LENGTH_MEASURE(5.));"));
  ASSERT_TRUE(r.ok()) << dump(r);
  const Model& m = r.model;
  ASSERT_EQ(m.instances().size(), 2u);
  const Instance* point = m.find(1);
  ASSERT_NE(point, nullptr);
  EXPECT_EQ(m.type_name(*point), "CARTESIAN_POINT");
  const auto p = m.params(*point);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(m.as_string(p[0]), "p");
  ASSERT_TRUE(p[1].is_list());
  const auto xyz = m.items(p[1]);
  ASSERT_EQ(xyz.size(), 3u);
  EXPECT_DOUBLE_EQ(m.as_real(xyz[0]), 1.5);
  EXPECT_DOUBLE_EQ(m.as_real(xyz[1]), -2.0);
  EXPECT_DOUBLE_EQ(m.as_real(xyz[2]), 30.0);

  const auto t = m.params(*m.find(2));
  ASSERT_EQ(t.size(), 9u);
  EXPECT_EQ(t[0].kind(), ValueKind::Omitted);
  EXPECT_EQ(t[1].kind(), ValueKind::Derived);
  EXPECT_EQ(m.as_integer(t[2]), 42);
  EXPECT_EQ(m.as_logical(t[3]), Logical::True);
  EXPECT_EQ(t[4].kind(), ValueKind::Binary);
  EXPECT_EQ(m.slice(t[4]), "1F");
  ASSERT_TRUE(t[5].is_reference());
  EXPECT_EQ(t[5].id(), 1u);
  EXPECT_EQ(t[6].count(), 0u);
  const auto nested = m.items(t[7]);
  ASSERT_EQ(nested.size(), 2u);
  EXPECT_EQ(m.items(nested[0]).size(), 2u);
  EXPECT_EQ(m.as_integer(m.items(nested[1])[0]), 3);
  ASSERT_EQ(t[8].kind(), ValueKind::Typed);
  EXPECT_EQ(m.keyword(t[8].keyword_id()), "LENGTH_MEASURE");
  EXPECT_DOUBLE_EQ(m.as_real(m.typed_child(t[8])), 5.0);
}

TEST(Reader, ForwardReferencesResolve) {
  const auto r = read(wrap("#1=A(#3);\n#3=B(#1);"));
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.model.find(r.model.params(*r.model.find(1))[0].id())->id, 3u);
}

TEST(Reader, ComplexInstance) {
  const auto r =
      read(wrap("#10=(GEOMETRIC_CONTEXT(3)GLOBAL_UNITS((#11))REPRESENTATION_CONTEXT('','3D'));\n"
                "#11=UNIT();"));
  ASSERT_TRUE(r.ok()) << dump(r);
  const Model& m = r.model;
  const Instance& c = *m.find(10);
  EXPECT_TRUE(m.is_complex(c));
  EXPECT_EQ(c.count, 3u);
  EXPECT_TRUE(m.has_type(c, "global_units"));
  const auto ctx = m.record_params(c, "REPRESENTATION_CONTEXT");
  ASSERT_TRUE(ctx.has_value());
  EXPECT_EQ(m.as_string((*ctx)[1]), "3D");
  EXPECT_FALSE(m.record_params(c, "NOT_THERE").has_value());
}

TEST(Reader, HeaderEntities) {
  const auto r = read(wrap("#1=A();"));
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.model.header().size(), 3u);
  const Instance* name = r.model.header_entity("FILE_NAME");
  ASSERT_NE(name, nullptr);
  EXPECT_EQ(r.model.as_string(r.model.params(*name)[0]), "t");
}

TEST(Reader, CommentBeforeMagicAndEverywhere) {
  const auto r = read(
      "/* before */ ISO-10303-21; /* c */ HEADER; FILE_DESCRIPTION(/*x*/('d'),'2;1');"
      "FILE_NAME('n','t',(''),(''),'','','');FILE_SCHEMA(('S'));ENDSEC;"
      "DATA;#1=/*y*/A(1/*z*/,2);ENDSEC;END-ISO-10303-21;");
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.model.params(*r.model.find(1)).size(), 2u);
}

TEST(Reader, SeveralNamedDataSections) {
  const auto r = read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'3;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA(('A','B'));ENDSEC;"
      "DATA('first',('A'));#1=X(#2);ENDSEC;"
      "DATA('second',('B'));#2=Y();#3=Z();ENDSEC;END-ISO-10303-21;");
  ASSERT_TRUE(r.ok()) << dump(r);
  ASSERT_EQ(r.model.sections().size(), 2u);
  const auto& second = r.model.sections()[1];
  EXPECT_EQ(second.end_instance - second.first_instance, 2u);
  EXPECT_EQ(second.param_count, 2u);
  EXPECT_EQ(r.model.as_string(r.model.all_values()[second.first_param]), "second");
}

TEST(Reader, Edition3AnchorReferenceSignature) {
  const auto r = read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'4;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA(('S'));ENDSEC;\n"
      "ANCHOR;<P1>=#1;<P2>=$;<LIST>=(#1,2);ENDSEC;\n"
      "REFERENCE;#11=<http://example.org/f.stp#v1>;ENDSEC;\n"
      "DATA;#1=P(#11);ENDSEC;END-ISO-10303-21;\n"
      "SIGNATURE\nAbC+/d==\nENDSEC;\n");
  EXPECT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(codes(r), std::vector<std::string>{"P21-043"});
  ASSERT_EQ(r.model.anchors().size(), 3u);
  const Instance* external = r.model.find(11);
  ASSERT_NE(external, nullptr);
  EXPECT_EQ(external->keyword, Model::kExternalKeyword);
}

TEST(Reader, LowerCaseKeywordsAreAccepted) {
  const auto r = read(wrap("#1 = drc(cdl((#2,#3)));\n#2 = dre(4.5);\n#3 = dre(2.0);"));
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.model.instances_of("DRE").size(), 2u);
}

TEST(Reader, KeywordIndex) {
  const auto r = read(wrap("#1=A();#2=B();#3=A();#4=(A()B());"));
  ASSERT_TRUE(r.ok());
  const auto as = r.model.instances_of("a");
  ASSERT_EQ(as.size(), 2u);  // simple instances only; complex ones are under (complex)
  EXPECT_EQ(as[0]->id, 1u);
  EXPECT_EQ(as[1]->id, 3u);
}

TEST(Reader, SparseIdsUseTheSortedIndex) {
  const auto r = read(wrap("#1000000000000=A(#5);#5=B();#77777777777=C();"));
  ASSERT_TRUE(r.ok()) << dump(r);
  ASSERT_NE(r.model.find(1000000000000ull), nullptr);
  EXPECT_EQ(r.model.type_name(*r.model.find(77777777777ull)), "C");
  EXPECT_EQ(r.model.find(6), nullptr);
}

TEST(Reader, DeepButAllowedNesting) {
  std::string nested = "#1=A(";
  for (int i = 0; i < 60; ++i) nested += '(';
  nested += '1';
  for (int i = 0; i < 60; ++i) nested += ')';
  nested += ");";
  const auto r = read(wrap(nested));
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.model.max_depth(), 61u);
}

TEST(Reader, ArenaIsContiguousPerInstance) {
  // The writer and the reference check rely on children being stored before their parents.
  const auto r = read(wrap("#1=A((1,(2,3)),4);"));
  ASSERT_TRUE(r.ok());
  const Instance& i = *r.model.find(1);
  const auto params = r.model.params(i);
  const auto outer = r.model.items(params[0]);
  EXPECT_LT(outer[1].first(), params[0].first());
  EXPECT_LT(params[0].first(), i.first);
}

}  // namespace
}  // namespace ncpost::p21
