// The ETag's hash (server/body_hash.hpp) is libxxhash's XXH64: the same values as the
// hand-written XXH64 it replaced, whole and fed in pieces of every size an upload arrives in,
// so that ETags a client holds stay valid across the change.

#include "body_hash.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace ncpost::server {
namespace {

// A megabyte of varied bytes, the same on every machine.
std::string varied_text() {
  std::string text(std::size_t{1} << 20, '\0');
  std::uint32_t x = 12345;
  for (char& c : text) {
    x = x * 1664525u + 1013904223u;
    c = static_cast<char>(x >> 24);
  }
  return text;
}

TEST(BodyHashPinned, SameValueAsBeforeWholeAndInPieces) {
  // Computed with the hand-written XXH64 before it was replaced by libxxhash.
  constexpr std::uint64_t kPinned = 0x3ef1307894b711aaULL;
  const std::string text = varied_text();
  EXPECT_EQ(body_hash(text), kPinned);
  for (const std::size_t piece : {1u, 7u, 31u, 32u, 33u, 4096u, 65537u}) {
    BodyHash h;
    for (std::size_t at = 0; at < text.size(); at += piece)
      h.update(std::string_view(text).substr(at, piece));
    EXPECT_EQ(h.digest(), kPinned) << "in pieces of " << piece;
  }
}

TEST(BodyHashPinned, MovedHashGoesOn) {
  BodyHash first;
  first.update("ISO-10303-21;");
  BodyHash second = std::move(first);
  second.update("END-ISO-10303-21;");
  EXPECT_EQ(second.digest(), body_hash("ISO-10303-21;END-ISO-10303-21;"));
}

}  // namespace
}  // namespace ncpost::server
