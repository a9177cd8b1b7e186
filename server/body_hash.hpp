#pragma once
// The hash of an upload for the ETag of a post: XXH64 (seed 0), computed as the bytes arrive so
// that nothing is left to hash when the upload ends. XXH64 because it streams, runs at several
// GB/s, and its published test vectors pin it down; an ETag needs a stable, well-mixed hash, not
// a cryptographic one (the program it names is recomputed by anyone who sends the same input).
// The hash itself is Debian's libxxhash (docs/dependencies.md), the reference implementation.

#include <cstdint>
#include <memory>
#include <string_view>

namespace ncpost::server {

class BodyHash {
 public:
  BodyHash();
  BodyHash(BodyHash&&) noexcept;
  BodyHash& operator=(BodyHash&&) noexcept;
  ~BodyHash();

  void update(std::string_view bytes);
  [[nodiscard]] std::uint64_t digest() const;

 private:
  struct State;  // libxxhash's XXH64_state_t, kept out of this header
  std::unique_ptr<State> state_;
};

[[nodiscard]] std::uint64_t body_hash(std::string_view bytes);

}  // namespace ncpost::server
