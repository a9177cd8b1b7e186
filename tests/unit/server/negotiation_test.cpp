// The header readings of server/negotiation.hpp against the RFCs' own examples and the cases
// the hostile review found (issue 23: 6, 7, 10, 12).

#include "negotiation.hpp"

#include <gtest/gtest.h>

namespace ncpost::server {
namespace {

// Three forms offered (the trace: text, JSON, NDJSON): the same rules pick one.
TEST(AcceptChoice, ThreeForms) {
  const auto choice = [](std::string_view accept) {
    return accept_choice(accept, {"text/plain", "application/json", "application/x-ndjson"});
  };
  EXPECT_EQ(choice(""), 0u);
  EXPECT_EQ(choice("*/*"), 0u);
  EXPECT_EQ(choice("application/json"), 1u);
  EXPECT_EQ(choice("application/x-ndjson"), 2u);
  EXPECT_EQ(choice("application/*"), 1u) << "a tie goes to the earlier offer";
  EXPECT_EQ(choice("application/json;q=0.5, application/x-ndjson"), 2u);
  EXPECT_EQ(choice("application/x-ndjson;q=0, */*"), 0u);
  EXPECT_EQ(choice("image/png"), 0u) << "nothing acceptable: the default";
}

TEST(AcceptPrefersJson, MediaRangesAndQValues) {
  EXPECT_FALSE(accept_prefers_json(""));
  EXPECT_FALSE(accept_prefers_json("text/plain"));
  EXPECT_TRUE(accept_prefers_json("application/json"));
  EXPECT_TRUE(accept_prefers_json("APPLICATION/JSON")) << "media types are case-insensitive";
  EXPECT_TRUE(accept_prefers_json("Application/Json; charset=utf-8"));
  // A substring is not a preference: the q-values decide.
  EXPECT_FALSE(accept_prefers_json("application/json;q=0.1, text/plain"));
  EXPECT_TRUE(accept_prefers_json("text/plain;q=0.5, application/json"));
  EXPECT_FALSE(accept_prefers_json("application/json;q=0"));
  EXPECT_TRUE(accept_prefers_json("application/*, text/plain;q=0.9"));
  // Equal q: the more specific range wins.
  EXPECT_TRUE(accept_prefers_json("*/*, application/json"));
  EXPECT_FALSE(accept_prefers_json("*/*"));
  EXPECT_FALSE(accept_prefers_json("*/*, text/plain"));
  // The most specific range for a type decides its q, whatever the order.
  EXPECT_FALSE(accept_prefers_json("application/json;q=0.2, application/*;q=1, text/*;q=0.5"));
  // Malformed ranges and q-values are ignored, not guessed at.
  EXPECT_FALSE(accept_prefers_json("application/json;q=2"));
  EXPECT_FALSE(accept_prefers_json("application/json;q=0.1234"));
  EXPECT_FALSE(accept_prefers_json("json"));
  EXPECT_TRUE(accept_prefers_json("garbage, application/json"));
}

TEST(NoneMatch, WeakComparisonListsAndStar) {
  const std::string_view etag = "\"abc\"";
  EXPECT_TRUE(none_match_matches("\"abc\"", etag));
  EXPECT_TRUE(none_match_matches("W/\"abc\"", etag));
  EXPECT_TRUE(none_match_matches("\"abc\"", "W/\"abc\""));
  EXPECT_TRUE(none_match_matches("*", etag));
  EXPECT_TRUE(none_match_matches("\"x\", W/\"abc\" , \"y\"", etag));
  EXPECT_TRUE(none_match_matches("\"a,b\", \"abc\"", etag)) << "a comma inside a tag";
  EXPECT_FALSE(none_match_matches("\"abcd\"", etag));
  EXPECT_FALSE(none_match_matches("\"x\", \"y\"", etag));
  EXPECT_FALSE(none_match_matches("", etag));
  EXPECT_FALSE(none_match_matches("abc", etag)) << "an unquoted tag is not the tag";
}

TEST(AttachmentDisposition, AsciiFallbackAndUtf8Name) {
  EXPECT_EQ(attachment_disposition("bracket.stp", ".ngc"), "attachment; filename=\"bracket.ngc\"");
  EXPECT_EQ(attachment_disposition("", ".nc"), "attachment; filename=\"program.nc\"");
  EXPECT_EQ(attachment_disposition("C:\\jobs\\part-7.stp", ".nc"),
            "attachment; filename=\"part-7.nc\"");
  EXPECT_EQ(attachment_disposition("Teil \xC3\x98 50.stp", ".nc"),
            "attachment; filename=\"Teil___50.nc\"; filename*=UTF-8''Teil%20%C3%98%2050.nc");
  // Quotes and control characters never reach the header; malformed UTF-8 becomes '_'.
  EXPECT_EQ(attachment_disposition("a\"b\r\nc.stp", ".nc"), "attachment; filename=\"a_b__c.nc\"");
  const std::string broken = attachment_disposition("x\xFFy.stp", ".nc");
  EXPECT_EQ(broken.find('\xFF'), std::string::npos) << broken;
  EXPECT_EQ(ascii_file_stem("\xE5\x9B\xBE.stp"), "_") << "one '_' per character, not per byte";
}

TEST(Query, PercentDecodeAndRepeatedParameters) {
  EXPECT_EQ(percent_decode("a%20b+c%2Fd"), "a b c/d");
  EXPECT_EQ(percent_decode("100%"), "100%");
  EXPECT_EQ(percent_decode("%zz%4"), "%zz%4");
  EXPECT_EQ(repeated_query_parameter("/v1/posts?profile=a&profile=b"), "profile");
  EXPECT_EQ(repeated_query_parameter("/v1/posts?profile=a&strict=true&strict=false"), "strict");
  EXPECT_EQ(repeated_query_parameter("/v1/posts?pro%66ile=a&profile=b"), "profile")
      << "names compare decoded";
  EXPECT_EQ(repeated_query_parameter("/v1/posts?profile=a&name=b"), "");
  EXPECT_EQ(repeated_query_parameter("/v1/posts"), "");
  EXPECT_EQ(repeated_query_parameter("/v1/posts?"), "");
}

}  // namespace
}  // namespace ncpost::server
