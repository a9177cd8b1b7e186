#pragma once
// ISO 10303-21 string literals: decoding the escaped form to UTF-8, and encoding UTF-8 back.
//
// Decoding handles every control directive of ed.2 and ed.3: '' and \\, \S\c (ISO 8859 page,
// default page 1), \P?\ (page switch), \X\hh (ISO 8859-1 byte), \X2\hhhh...\X0\ (UCS-2, with
// surrogate pairs) and \X4\hhhhhhhh...\X0\ (UCS-4), plus raw UTF-8 (ed.3 high code points).
// A backslash that starts no directive is kept as a literal backslash (Windows paths).
// Line breaks inside a literal are not significant (ISO 10303-21 lets writers break lines
// anywhere) and are dropped. Anything malformed decodes to U+FFFD; the reader reports it.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace ncpost::p21 {

// `raw` is the text between the apostrophes.
void decode_string(std::string_view raw, std::string& out);

struct StringProblem {
  enum Kind : std::uint8_t {
    None,
    Encoding,       // bytes that are not UTF-8, control characters, non-Latin-1 pages
    LoneBackslash,  // '\' starting no directive; kept as a literal backslash
    Malformed,      // a broken \X\, \X2\ or \X4\ directive
  };
  Kind kind = None;
  std::size_t offset = 0;  // within the raw literal
  std::string message;
};

// The most serious problem in `raw` (the first of that kind), for the reader's validation.
[[nodiscard]] StringProblem check_string(std::string_view raw);

// Encodes UTF-8 text as a P21 literal body (without the apostrophes): printable ASCII stays,
// ' and \ are doubled, everything else becomes \X2\ or \X4\ runs. Invalid UTF-8 becomes U+FFFD.
void encode_string(std::string_view utf8, std::string& out);

// Appends the UTF-8 encoding of one code point (U+FFFD for invalid ones).
void append_utf8(char32_t code_point, std::string& out);

}  // namespace ncpost::p21
