#pragma once
// One parameter value of an ISO 10303-21 instance, packed into 8 bytes.
//
// Text-like values (numbers, strings, enumerations, binaries, keywords) are slices of the model's
// text buffer: they are validated while reading but converted only when asked (IfcParse's idea),
// which keeps reading fast and the model small. Lists and typed parameters point to their
// children in the model's value arena.

#include <cstdint>

namespace ncpost::p21 {

enum class ValueKind : std::uint8_t {
  Omitted,       // $
  Derived,       // *
  Integer,       // text slice
  Real,          // text slice
  String,        // text slice between the apostrophes, still escaped
  Enumeration,   // text slice between the dots, e.g. T for .T.
  Binary,        // text slice between the quotes
  Reference,     // #123: the instance id
  ConstantName,  // #NAME or @NAME (ed.3 constants): text slice without the sigil
  ValueName,     // @123 (ed.3 value instance): text slice without the sigil
  Resource,      // <uri> (ed.3 anchors and references): text slice between < >
  List,          // ( ... ): `count` children starting at `first`
  Typed,         // KEYWORD( value ): keyword id and one child
};

class Value {
 public:
  static constexpr std::uint32_t kMaxSliceLength = (1u << 27) - 1;
  static constexpr std::uint64_t kMaxId = (std::uint64_t{1} << 60) - 1;

  constexpr Value() = default;

  static constexpr Value omitted() { return Value(ValueKind::Omitted, 0, 0); }
  static constexpr Value derived() { return Value(ValueKind::Derived, 0, 0); }
  // `needs_decoding` is the string flag: the slice has escapes, doubled apostrophes, line breaks
  // or non-ASCII bytes, so decoding is more than a copy.
  static constexpr Value slice(ValueKind kind, std::uint32_t offset, std::uint32_t length,
                               bool needs_decoding = false) {
    return Value(kind, (length << 1) | (needs_decoding ? 1u : 0u), offset);
  }
  static constexpr Value reference(std::uint64_t id) {
    return Value((std::uint64_t{static_cast<std::uint8_t>(ValueKind::Reference)} << 60) | id);
  }
  static constexpr Value list(std::uint32_t first, std::uint32_t count) {
    return Value(ValueKind::List, count, first);
  }
  static constexpr Value typed(std::uint32_t keyword_id, std::uint32_t child) {
    return Value(ValueKind::Typed, keyword_id, child);
  }

  [[nodiscard]] constexpr ValueKind kind() const { return static_cast<ValueKind>(bits_ >> 60); }
  // Slices.
  [[nodiscard]] constexpr std::uint32_t offset() const { return low(); }
  [[nodiscard]] constexpr std::uint32_t length() const { return high() >> 1; }
  [[nodiscard]] constexpr bool needs_decoding() const { return (high() & 1u) != 0; }
  // References.
  [[nodiscard]] constexpr std::uint64_t id() const { return bits_ & kMaxId; }
  // Lists.
  [[nodiscard]] constexpr std::uint32_t first() const { return low(); }
  [[nodiscard]] constexpr std::uint32_t count() const { return high(); }
  // Typed parameters.
  [[nodiscard]] constexpr std::uint32_t keyword_id() const { return high(); }
  [[nodiscard]] constexpr std::uint32_t child() const { return low(); }

  [[nodiscard]] constexpr bool is_omitted() const { return kind() == ValueKind::Omitted; }
  [[nodiscard]] constexpr bool is_list() const { return kind() == ValueKind::List; }
  [[nodiscard]] constexpr bool is_reference() const { return kind() == ValueKind::Reference; }
  [[nodiscard]] constexpr bool is_number() const {
    return kind() == ValueKind::Integer || kind() == ValueKind::Real;
  }

  friend constexpr bool operator==(Value, Value) = default;

 private:
  constexpr explicit Value(std::uint64_t bits) : bits_(bits) {}
  // Layout: kind (4 bits) | high (28 bits) | low (32 bits).
  constexpr Value(ValueKind kind, std::uint32_t high, std::uint32_t low)
      : bits_((std::uint64_t{static_cast<std::uint8_t>(kind)} << 60) |
              (std::uint64_t{high & 0x0FFFFFFFu} << 32) | low) {}
  [[nodiscard]] constexpr std::uint32_t high() const {
    return static_cast<std::uint32_t>(bits_ >> 32) & 0x0FFFFFFFu;
  }
  [[nodiscard]] constexpr std::uint32_t low() const { return static_cast<std::uint32_t>(bits_); }

  std::uint64_t bits_ = 0;
};

static_assert(sizeof(Value) == 8);

}  // namespace ncpost::p21
