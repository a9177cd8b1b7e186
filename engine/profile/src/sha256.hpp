#pragma once
// SHA-256 (FIPS 180-4) for profile versions: a content hash that names version folders and
// goes into the server's ETag. The digest is nettle's (Debian's nettle-dev, docs/dependencies.md):
// a well-kept, small library whose only job is such primitives.

#include <nettle/sha2.h>

#include <string>
#include <string_view>

namespace ncpost::profile::detail {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  // Hex digest (64 lower-case digits). Call once.
  [[nodiscard]] std::string hex();

 private:
  sha256_ctx context_;
};

[[nodiscard]] std::string sha256_hex(std::string_view bytes);

}  // namespace ncpost::profile::detail
