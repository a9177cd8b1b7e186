#pragma once
// Where a P21 text that is still arriving may be cut for reading: just after a ';' that is
// outside any string, comment or resource, so that no token straddles the cut and the reader
// stops between instances. It tracks those three states the way the lexer enters and leaves
// them; where a malformed file could make it disagree with the lexer (a runaway string), the cut
// lands inside a token, the lexer reports the token as broken, and p21::StreamReader then reads the
// whole text again. So a wrong cut costs time, never a different result.

#include <cstddef>
#include <cstdint>

namespace ncpost::p21::detail {

class CutFinder {
 public:
  // Looks at the bytes [scanned(), end) of `text` (the same text every call, grown).
  void scan(const char* text, std::size_t end) {
    std::size_t i = scanned_;
    while (i < end) {
      const char c = text[i];
      switch (state_) {
        case State::Normal:
          if (c == ';') {
            cut_ = i + 1;
          } else if (c == '\'') {
            state_ = State::String;
          } else if (c == '<') {
            state_ = State::Resource;
          } else if (c == '/') {
            if (i + 1 == end) {  // is it "/*"? Decided when the next byte is there.
              scanned_ = i;
              return;
            }
            if (text[i + 1] == '*') {
              state_ = State::Comment;
              ++i;  // the '*' of "/*" does not close the comment: "/*/" is still open
            }
          }
          break;
        case State::String:  // a doubled apostrophe leaves and re-enters: still inside
          if (c == '\'') {
            state_ = State::Normal;
          } else if (c == '\\') {
            // \S\ takes the next character whatever it is, even an apostrophe (as the lexer).
            if (end - i < 4) {
              scanned_ = i;
              return;
            }
            if (text[i + 1] == 'S' && text[i + 2] == '\\' && text[i + 3] != '\n') i += 3;
          }
          break;
        case State::Resource:  // the lexer ends a resource at '>' or at the end of the line
          if (c == '>' || c == '\n') state_ = State::Normal;
          break;
        case State::Comment:
          if (c == '*') {
            if (i + 1 == end) {
              scanned_ = i;
              return;
            }
            if (text[i + 1] == '/') {
              state_ = State::Normal;
              ++i;
            }
          }
          break;
      }
      ++i;
    }
    scanned_ = end;
  }
  [[nodiscard]] std::size_t scanned() const { return scanned_; }
  // Just past the last ';' found outside literals and comments; 0 before the first.
  [[nodiscard]] std::size_t cut() const { return cut_; }

 private:
  enum class State : std::uint8_t { Normal, String, Resource, Comment };
  State state_ = State::Normal;
  std::size_t scanned_ = 0;
  std::size_t cut_ = 0;
};

}  // namespace ncpost::p21::detail
