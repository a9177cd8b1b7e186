#include "auth.hpp"

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace ncpost::server {

namespace {

constexpr std::size_t kMinimumLength = 16;
// A token longer than this is surely a wrong file (a key, a certificate); also bounds the work
// of a comparison.
constexpr std::size_t kMaximumLength = 4096;

bool is_space(char c) noexcept {
  return c == ' ' || c == '\t';
}

char lower(char c) noexcept {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

// "visible ASCII": what an HTTP header can carry unquoted, and what a shell and an
// environment variable hold without surprises.
bool printable(std::string_view token) noexcept {
  for (const char c : token)
    if (c < 0x21 || c > 0x7e) return false;
  return true;
}

std::optional<std::string> checked(std::string token, const std::string& source,
                                   std::vector<std::string>& errors,
                                   std::vector<std::string>& warnings) {
  if (token.empty()) {
    errors.push_back("the admin token from " + source + " is empty");
    return std::nullopt;
  }
  if (token.size() > kMaximumLength) {
    errors.push_back("the admin token from " + source + " is longer than " +
                     std::to_string(kMaximumLength) + " characters");
    return std::nullopt;
  }
  if (!printable(token)) {
    errors.push_back("the admin token from " + source +
                     " has spaces or control characters (only visible ASCII is allowed)");
    return std::nullopt;
  }
  if (token.size() < kMinimumLength) {
    warnings.push_back("the admin token from " + source + " is shorter than " +
                       std::to_string(kMinimumLength) + " characters; use a long random one");
  }
  return token;
}

}  // namespace

bool token_matches(std::string_view expected, std::string_view header) noexcept {
  constexpr std::string_view kScheme = "bearer";
  if (header.size() <= kScheme.size() || !is_space(header[kScheme.size()])) return false;
  for (std::size_t i = 0; i < kScheme.size(); ++i)
    if (lower(header[i]) != kScheme[i]) return false;
  std::string_view given = header.substr(kScheme.size());
  while (!given.empty() && is_space(given.front())) given.remove_prefix(1);
  while (!given.empty() && is_space(given.back())) given.remove_suffix(1);
  if (expected.empty() || given.empty()) return false;
  // Every byte of the given token is compared with a byte of the expected one (cycled), and
  // the differences are OR-ed together without an early exit: the loop runs given.size()
  // times whatever the contents. volatile keeps the compiler from adding a shortcut.
  volatile unsigned char diff = expected.size() == given.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    diff = static_cast<unsigned char>(diff |
                                      (static_cast<unsigned char>(given[i]) ^
                                       static_cast<unsigned char>(expected[i % expected.size()])));
  }
  return diff == 0;
}

std::optional<std::string> load_admin_token(const std::optional<std::filesystem::path>& file,
                                            std::vector<std::string>& errors,
                                            std::vector<std::string>& warnings) {
  if (file) {
    const std::string source = "the file " + file->string();
    std::ifstream in(*file, std::ios::binary);
    if (!in) {
      errors.push_back("cannot read the admin token file " + file->string());
      return std::nullopt;
    }
    std::ostringstream text;
    text << in.rdbuf();
    std::string token = text.str();
    if (!token.empty() && token.back() == '\n') token.pop_back();
    if (!token.empty() && token.back() == '\r') token.pop_back();
    struct stat st {};
    if (::stat(file->c_str(), &st) == 0 && (st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
      warnings.push_back("the admin token file " + file->string() +
                         " may be read by group or others; chmod 600 it");
    }
    return checked(std::move(token), source, errors, warnings);
  }
  if (const char* env = std::getenv("NCPOST_ADMIN_TOKEN"); env != nullptr) {
    return checked(env, "NCPOST_ADMIN_TOKEN", errors, warnings);
  }
  return std::nullopt;
}

std::optional<std::string> load_admin_token(const std::optional<std::filesystem::path>& file,
                                            std::vector<std::string>& errors) {
  std::vector<std::string> warnings;
  return load_admin_token(file, errors, warnings);
}

}  // namespace ncpost::server
