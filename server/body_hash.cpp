#include "body_hash.hpp"

#include <xxhash.h>

#include <new>

namespace ncpost::server {

struct BodyHash::State {
  State() : xxh(XXH64_createState()) {
    if (xxh == nullptr) throw std::bad_alloc();
    XXH64_reset(xxh, 0);
  }
  State(const State&) = delete;
  State& operator=(const State&) = delete;
  ~State() { XXH64_freeState(xxh); }
  XXH64_state_t* xxh;
};

BodyHash::BodyHash() : state_(std::make_unique<State>()) {}
BodyHash::BodyHash(BodyHash&&) noexcept = default;
BodyHash& BodyHash::operator=(BodyHash&&) noexcept = default;
BodyHash::~BodyHash() = default;

void BodyHash::update(std::string_view bytes) {
  XXH64_update(state_->xxh, bytes.data(), bytes.size());
}

std::uint64_t BodyHash::digest() const {
  return XXH64_digest(state_->xxh);
}

std::uint64_t body_hash(std::string_view bytes) {
  return XXH64(bytes.data(), bytes.size(), 0);
}

}  // namespace ncpost::server
