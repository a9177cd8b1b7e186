// Every string escape of ISO 10303-21, decoded lazily through the Model and directly.

#include "ncpost/p21/strings.hpp"

#include <gtest/gtest.h>

#include "ncpost/p21/reader.hpp"
#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

std::string decoded(std::string_view raw) {
  std::string out;
  decode_string(raw, out);
  return out;
}

TEST(Strings, DoubledApostropheAndBackslash) {
  EXPECT_EQ(decoded("it''s"), "it's");
  EXPECT_EQ(decoded("C:\\\\dir"), "C:\\dir");
}

TEST(Strings, PageDirective) {
  EXPECT_EQ(decoded("\\S\\D"), "\xC3\x84");  // 'D' + 0x80 = 0xC4 = Ä
  EXPECT_EQ(decoded("\\S\\'"), "\xC2\xA7");  // 0x27 + 0x80 = 0xA7 = §
}

TEST(Strings, AlphabetDirective) {
  EXPECT_EQ(decoded("\\PA\\x\\S\\D"), "x\xC3\x84");
  EXPECT_EQ(check_string("\\PE\\x").kind, StringProblem::Encoding);  // only part 1 is linear
}

TEST(Strings, ArbitraryByte) {
  EXPECT_EQ(decoded("\\X\\E9t\\X\\E9"), "\xC3\xA9t\xC3\xA9");
}

TEST(Strings, Extended2) {
  EXPECT_EQ(decoded("\\X2\\041A0440\\X0\\"), "\xD0\x9A\xD1\x80");  // Кр
  EXPECT_EQ(decoded("a\\X2\\00E9\\X0\\b"),
            "a\xC3\xA9"
            "b");
}

TEST(Strings, Extended2SurrogatePair) {
  EXPECT_EQ(decoded("\\X2\\D83DDE00\\X0\\"), "\xF0\x9F\x98\x80");  // U+1F600
}

TEST(Strings, Extended4) {
  EXPECT_EQ(decoded("\\X4\\0001F600\\X0\\"), "\xF0\x9F\x98\x80");
}

TEST(Strings, RawUtf8IsEdition3) {
  EXPECT_EQ(decoded("caf\xC3\xA9"), "caf\xC3\xA9");
  EXPECT_EQ(check_string("caf\xC3\xA9").kind, StringProblem::None);
}

TEST(Strings, InvalidUtf8BecomesReplacement) {
  EXPECT_EQ(decoded("a\xD8"
                    "b"),
            "a\xEF\xBF\xBD"
            "b");
  EXPECT_EQ(check_string("a\xD8"
                         "b")
                .kind,
            StringProblem::Encoding);
}

TEST(Strings, LineBreaksAreDropped) {
  EXPECT_EQ(decoded("ab\r\ncd"), "abcd");
}

TEST(Strings, PrintControlDirectivesAreDropped) {
  EXPECT_EQ(decoded("a\\N\\b\\F\\c"), "abc");
}

TEST(Strings, MalformedDirectives) {
  EXPECT_EQ(check_string("\\X\\G1").kind, StringProblem::Malformed);
  EXPECT_EQ(check_string("\\X2\\00E").kind, StringProblem::Malformed);
  EXPECT_EQ(check_string("\\X2\\00E9").kind, StringProblem::Malformed);  // no \X0\ terminator
  EXPECT_EQ(check_string("\\X4\\0041\\X0\\").kind, StringProblem::Malformed);
  EXPECT_EQ(decoded("\\X2\\00E9"), "\xC3\xA9\xEF\xBF\xBD");
}

TEST(Strings, LoneBackslashIsLiteral) {
  EXPECT_EQ(decoded("C:\\Users\\x"), "C:\\Users\\x");
  EXPECT_EQ(check_string("C:\\Users").kind, StringProblem::LoneBackslash);
}

TEST(Strings, EncodeRoundTrips) {
  for (std::string text :
       std::initializer_list<std::string>{"plain", "it's \\ here", "caf\xC3\xA9 \xD0\x9A",
                                          "\xF0\x9F\x98\x80 x", std::string("tab\there")}) {
    std::string encoded;
    encode_string(text, encoded);
    for (char c : encoded) EXPECT_TRUE(c >= 0x20 && c < 0x7F) << encoded;
    EXPECT_EQ(check_string(encoded).kind, StringProblem::None) << encoded;
    EXPECT_EQ(decoded(encoded), text) << encoded;
  }
}

TEST(Strings, DecodingIsLazyThroughTheModel) {
  const auto r = read(test::wrap("#1=A('\\X2\\00E9\\X0\\t\\S\\D','plain');"));
  ASSERT_TRUE(r.ok()) << test::dump(r);
  const auto p = r.model.params(*r.model.find(1));
  EXPECT_TRUE(p[0].needs_decoding());
  EXPECT_EQ(r.model.slice(p[0]), "\\X2\\00E9\\X0\\t\\S\\D");  // still raw in the model
  EXPECT_EQ(r.model.as_string(p[0]), "\xC3\xA9t\xC3\x84");
  EXPECT_FALSE(p[1].needs_decoding());
}

}  // namespace
}  // namespace ncpost::p21
