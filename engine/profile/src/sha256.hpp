#pragma once
// SHA-256 (FIPS 180-4) for profile versions: a content hash that names version folders and
// goes into the server's ETag. Written here because no Debian-packaged dependency of the
// project provides one (OpenSSL would be a new dependency for 100 lines).

#include <array>
#include <cstdint>
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
  void block(const unsigned char* p);
  std::array<std::uint32_t, 8> h_;
  std::array<unsigned char, 64> buffer_{};
  std::size_t used_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

[[nodiscard]] std::string sha256_hex(std::string_view bytes);

}  // namespace ncpost::profile::detail
