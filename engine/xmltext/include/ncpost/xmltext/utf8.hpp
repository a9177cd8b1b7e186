#pragma once
// UTF-8 validation, the one implementation that the P21 string decoder, the XML escaper and the
// canonical trace share.

#include <cstddef>
#include <string_view>

namespace ncpost::xmltext {

// Length (2 to 4) of the valid multi-byte UTF-8 sequence at s[pos], with its code point in `cp`;
// 1 for an ASCII byte; 0 when the bytes there are not valid UTF-8 (bad lead or continuation
// bytes, overlong forms, surrogates, beyond U+10FFFF, or cut short by the end of `s`).
[[nodiscard]] std::size_t utf8_sequence_length(std::string_view s, std::size_t pos,
                                               char32_t& cp) noexcept;

}  // namespace ncpost::xmltext
