#pragma once
// The hash of an upload for the ETag of a post: XXH64 (seed 0), computed as the bytes arrive so
// that nothing is left to hash when the upload ends. XXH64 because it streams, runs at several
// GB/s, and its published test vectors pin it down; an ETag needs a stable, well-mixed hash, not
// a cryptographic one (the program it names is recomputed by anyone who sends the same input).
// Written from the published algorithm: no Debian package of the project's set provides it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ncpost::server {

class BodyHash {
 public:
  void update(std::string_view bytes);
  [[nodiscard]] std::uint64_t digest() const;

 private:
  static constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ULL;
  static constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4FULL;
  std::array<std::uint64_t, 4> lanes_ = {kPrime1 + kPrime2, kPrime2, 0, 0 - kPrime1};
  std::array<unsigned char, 32> pending_{};  // the start of a 32-byte stripe not yet complete
  std::size_t pending_size_ = 0;
  std::uint64_t length_ = 0;
};

[[nodiscard]] std::uint64_t body_hash(std::string_view bytes);

}  // namespace ncpost::server
