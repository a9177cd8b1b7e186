// server/auth: the bearer-token check of PUT/DELETE /v1/profiles and where the token comes
// from. Built here, from the source file, so that it needs neither Boost nor the server target.

#include "auth.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>

namespace ncpost::server {
namespace {

namespace fs = std::filesystem;

TEST(TokenMatches, AcceptsOnlyTheExactBearerToken) {
  const std::string token = "s3cret-Token_0123456789";
  EXPECT_TRUE(token_matches(token, "Bearer " + token));
  EXPECT_TRUE(token_matches(token, "bearer " + token)) << "the scheme is case-insensitive";
  EXPECT_TRUE(token_matches(token, "BEARER   " + token + "  "));
  EXPECT_FALSE(token_matches(token, "Bearer " + token + "x"));
  EXPECT_FALSE(token_matches(token, "Bearer " + token.substr(1)));
  EXPECT_FALSE(token_matches(token, "Bearer " + token.substr(0, token.size() - 1)));
  EXPECT_FALSE(token_matches(token, "Bearer S3cret-Token_0123456789"))
      << "tokens are case-sensitive";
  EXPECT_FALSE(token_matches(token, token)) << "no scheme";
  EXPECT_FALSE(token_matches(token, "Basic " + token));
  EXPECT_FALSE(token_matches(token, "Bearer" + token)) << "no space after the scheme";
  EXPECT_FALSE(token_matches(token, "Bearer "));
  EXPECT_FALSE(token_matches(token, ""));
  EXPECT_FALSE(token_matches("", "Bearer ")) << "an empty expected token matches nothing";
  EXPECT_FALSE(token_matches("", "Bearer x"));
  // A given token that repeats the expected one must not match (the comparison cycles).
  EXPECT_FALSE(token_matches("ab", "Bearer abab"));
}

// Not a timing proof (too noisy for CI), but the comparison must not stop at the first wrong
// byte: a wrong first byte and a wrong last byte take the same code path. This checks that
// both are refused with tokens of the maximum length, as a guard against an early-exit edit.
TEST(TokenMatches, LongTokens) {
  const std::string token(4096, 'k');
  std::string first = token, last = token;
  first.front() = 'x';
  last.back() = 'x';
  EXPECT_TRUE(token_matches(token, "Bearer " + token));
  EXPECT_FALSE(token_matches(token, "Bearer " + first));
  EXPECT_FALSE(token_matches(token, "Bearer " + last));
}

class AdminToken : public ::testing::Test {
 protected:
  void SetUp() override {
    ::unsetenv("NCPOST_ADMIN_TOKEN");
    file_ = fs::temp_directory_path() / ("ncpost-token-" + std::to_string(::getpid()));
  }
  void TearDown() override {
    ::unsetenv("NCPOST_ADMIN_TOKEN");
    fs::remove(file_);
  }
  void write(const std::string& text,
             fs::perms perms = fs::perms::owner_read | fs::perms::owner_write) {
    std::ofstream(file_, std::ios::binary | std::ios::trunc) << text;
    fs::permissions(file_, perms);
  }
  fs::path file_;
  std::vector<std::string> errors_, warnings_;
};

TEST_F(AdminToken, FromFileTrimmedNewline) {
  write("0123456789abcdef0123\n");
  ::setenv("NCPOST_ADMIN_TOKEN", "from-the-environment-000", 1);
  const auto t = load_admin_token(file_, errors_, warnings_);
  ASSERT_TRUE(t);
  EXPECT_EQ(*t, "0123456789abcdef0123") << "the file wins over the environment";
  EXPECT_TRUE(errors_.empty());
  EXPECT_TRUE(warnings_.empty());
  write("0123456789abcdef0123\r\n");
  EXPECT_EQ(load_admin_token(file_, errors_, warnings_).value_or(""), "0123456789abcdef0123");
}

TEST_F(AdminToken, RefusesEmptyAndBadTokens) {
  write("\n");
  EXPECT_FALSE(load_admin_token(file_, errors_, warnings_));
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_NE(errors_[0].find("empty"), std::string::npos);
  errors_.clear();
  write("two words here\n");
  EXPECT_FALSE(load_admin_token(file_, errors_, warnings_));
  EXPECT_EQ(errors_.size(), 1u);
  errors_.clear();
  EXPECT_FALSE(load_admin_token(file_ / "missing", errors_, warnings_));
  EXPECT_EQ(errors_.size(), 1u);
  errors_.clear();
  ::setenv("NCPOST_ADMIN_TOKEN", "", 1);
  EXPECT_FALSE(load_admin_token(std::nullopt, errors_, warnings_));
  EXPECT_EQ(errors_.size(), 1u);
}

TEST_F(AdminToken, WarnsOnReadableFileAndShortToken) {
  write("0123456789abcdef0123\n", fs::perms::owner_read | fs::perms::owner_write |
                                      fs::perms::group_read | fs::perms::others_read);
  EXPECT_TRUE(load_admin_token(file_, errors_, warnings_));
  EXPECT_TRUE(errors_.empty());
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("chmod 600"), std::string::npos);
  EXPECT_EQ(warnings_[0].find("0123456789abcdef0123"), std::string::npos) << "never the token";
  warnings_.clear();
  write("short\n");
  EXPECT_EQ(load_admin_token(file_, errors_, warnings_).value_or(""), "short");
  EXPECT_EQ(warnings_.size(), 1u);
}

TEST_F(AdminToken, FromEnvironmentElseNone) {
  EXPECT_FALSE(load_admin_token(std::nullopt, errors_)) << "none: writes are disabled";
  EXPECT_TRUE(errors_.empty());
  ::setenv("NCPOST_ADMIN_TOKEN", "env-token-0123456789", 1);
  EXPECT_EQ(load_admin_token(std::nullopt, errors_).value_or(""), "env-token-0123456789");
  EXPECT_TRUE(errors_.empty());
}

}  // namespace
}  // namespace ncpost::server
