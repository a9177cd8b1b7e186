// Model → P21 → Model gives the same model, and the text is valid P21.

#include "ncpost/p21/writer.hpp"

#include <gtest/gtest.h>

#include "ncpost/p21/compare.hpp"
#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

TEST(Writer, RoundTripKeepsEverything) {
  const std::string source =
      "ISO-10303-21;HEADER;FILE_DESCRIPTION(('d'),'3;1');FILE_NAME('n','t',('a'),('o'),'p','s','z')"
      ";"
      "FILE_SCHEMA(('A'));ENDSEC;ANCHOR;<P>=#1;ENDSEC;REFERENCE;#9=<f.stp#x>;ENDSEC;"
      "DATA('s1',('A'));#1=A('it''s \\X2\\00E9\\X0\\',(1.5,-2.,3),.T.,$,*,\"0F\",#2,#9,"
      "M(2.),#C1,@V);#2=(B(1)C('x'));ENDSEC;DATA;#3=D(());ENDSEC;END-ISO-10303-21;";
  const auto first = read(source);
  ASSERT_TRUE(first.ok()) << test::dump(first);
  const std::string written = write_to_string(first.model);
  const auto second = read(written);
  ASSERT_TRUE(second.ok()) << test::dump(second) << written;
  EXPECT_EQ(first_difference(first.model, second.model), std::nullopt) << written;
  EXPECT_NE(written.find("#2=(B(1)C('x'));"), std::string::npos) << written;
}

TEST(Writer, CompareFindsDifferences) {
  const auto a = read(test::wrap("#1=A(1.5,'x',(1,2));"));
  const auto b = read(test::wrap("#1=A(1.50,'x',(1,2));"));  // same value, other spelling
  const auto c = read(test::wrap("#1=A(1.5,'y',(1,2));"));
  const auto d = read(test::wrap("#1=A(1.5,'x',(1,3));"));
  const auto e = read(test::wrap("#1=B(1.5,'x',(1,2));"));
  EXPECT_EQ(first_difference(a.model, b.model), std::nullopt);
  EXPECT_NE(first_difference(a.model, c.model), std::nullopt);
  EXPECT_NE(first_difference(a.model, d.model), std::nullopt);
  EXPECT_NE(first_difference(a.model, e.model), std::nullopt);
}

TEST(Writer, StreamsInPieces) {
  std::string data;
  for (int i = 1; i <= 20000; ++i) data += "#" + std::to_string(i) + "=P((1.,2.,3.));\n";
  const auto r = read(test::wrap(data));
  ASSERT_TRUE(r.ok());
  std::size_t pieces = 0;
  std::size_t largest = 0;
  write(r.model, [&](std::string_view piece) {
    ++pieces;
    largest = std::max(largest, piece.size());
  });
  EXPECT_GT(pieces, 3u);
  EXPECT_LT(largest, 80u * 1024u);
}

}  // namespace
}  // namespace ncpost::p21
