#pragma once
// The admin token of PUT/DELETE /v1/profiles/{id} (docs/profile-admin.md): where it comes from
// and how a request's Authorization header is checked against it. The token is a secret: no
// function here logs it or puts it into a message.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::server {

// Whether `authorization_header` is "Bearer <token>" with exactly the expected token. The
// scheme is case-insensitive (RFC 9110 11.1), spaces around the token are ignored. The time
// taken depends on the lengths only, never on the contents of either token, so a client cannot
// learn the token a byte at a time. An empty `expected` matches nothing.
[[nodiscard]] bool token_matches(std::string_view expected,
                                 std::string_view authorization_header) noexcept;

// The admin token: read from `file` when given (one line; a trailing newline is trimmed), else
// from the environment variable NCPOST_ADMIN_TOKEN, else none (nullopt: writes are disabled,
// PUT/DELETE answer 401/403). A file that cannot be read, an empty token, or one with
// characters other than visible ASCII is an error: nullopt and a message in `errors` (the
// server should refuse to start). `warnings` gets what deserves a log line but still works: a
// token file that group or others may read, a token shorter than 16 characters.
[[nodiscard]] std::optional<std::string> load_admin_token(
    const std::optional<std::filesystem::path>& file, std::vector<std::string>& errors,
    std::vector<std::string>& warnings);
// The same without the warnings.
[[nodiscard]] std::optional<std::string> load_admin_token(
    const std::optional<std::filesystem::path>& file, std::vector<std::string>& errors);

}  // namespace ncpost::server
