#pragma once
// From text to records: physical lines (any piece boundaries), `$$` comments, `$`
// continuations, and the fields of a record, with line:column for every offset. No copies for
// the usual one-line record; a continued record is joined into one reused buffer.

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::cls::detail {

// One physical line's share of a record: where its text starts in the record and where that is
// in the file.
struct Segment {
  std::uint32_t offset = 0;
  std::uint32_t line = 0;
  std::uint32_t column = 1;
};

struct Position {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// One logical record: the statement (comments and continuation marks removed) and the
// comments written beside it (`$$ text`, or text after a continuation `$`), joined by spaces.
struct Record {
  std::string_view text;
  std::string_view comment;
  std::uint32_t comment_line = 0;
  std::uint32_t comment_column = 0;
  const std::vector<Segment>* segments = nullptr;

  [[nodiscard]] std::uint32_t line() const noexcept { return (*segments)[0].line; }
  [[nodiscard]] Position at(std::size_t offset) const noexcept;
  [[nodiscard]] Position at(std::string_view inside_text) const noexcept {
    return at(static_cast<std::size_t>(inside_text.data() - text.data()));
  }
};

// Splits pieces of text into lines and lines into records. on_record(const Record&) is called
// for every complete record (also for a line that is only a comment: empty text);
// on_too_long(first_line) for a record longer than max_bytes, which is skipped.
class RecordAssembler {
 public:
  explicit RecordAssembler(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  template <class OnRecord, class OnTooLong>
  void feed(std::string_view piece, OnRecord&& on_record, OnTooLong&& on_too_long) {
    while (!piece.empty()) {
      const std::size_t newline = piece.find('\n');
      if (newline == std::string_view::npos) {
        if (carry_.size() + piece.size() > max_bytes_ + 2) {
          if (!carry_too_long_) on_too_long(line_ + 1);
          carry_too_long_ = true;
          carry_.clear();
        } else {
          carry_.append(piece);
        }
        return;
      }
      std::string_view line = piece.substr(0, newline);
      piece.remove_prefix(newline + 1);
      if (carry_too_long_) {
        ++line_;
        carry_too_long_ = false;
        carry_.clear();
        continue;
      }
      if (!carry_.empty()) {
        carry_.append(line);
        line_done(carry_, on_record, on_too_long);
        carry_.clear();
      } else {
        line_done(line, on_record, on_too_long);
      }
    }
  }

  // The last line (without a newline) and whether a continued record was left open.
  template <class OnRecord, class OnTooLong>
  [[nodiscard]] bool finish(OnRecord&& on_record, OnTooLong&& on_too_long) {
    if (!carry_.empty() && !carry_too_long_) {
      std::string last;
      last.swap(carry_);
      line_done(last, on_record, on_too_long);
    }
    carry_.clear();
    return open_;
  }

  [[nodiscard]] std::uint32_t lines() const noexcept { return line_; }

 private:
  template <class OnRecord, class OnTooLong>
  void line_done(std::string_view line, OnRecord& on_record, OnTooLong& on_too_long) {
    ++line_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::string_view content = line;
    std::string_view comment;
    std::uint32_t comment_column = 0;
    bool continued = false;
    if (const std::size_t dollar = line.find('$'); dollar != std::string_view::npos) {
      content = line.substr(0, dollar);
      const bool remark = dollar + 1 < line.size() && line[dollar + 1] == '$';
      continued = !remark;
      const std::size_t from = dollar + (remark ? 2 : 1);
      comment = trim_comment(line.substr(from));
      comment_column = static_cast<std::uint32_t>(comment.data() - line.data()) + 1;
    }
    if (!open_ && !continued) {
      if (content.size() > max_bytes_) return on_too_long(line_);
      single_[0] = Segment{0, line_, 1};
      Record r{content, comment, line_, comment_column, &single_};
      on_record(static_cast<const Record&>(r));
      return;
    }
    if (!open_) {
      joined_.clear();
      comments_.clear();
      segments_.clear();
      too_long_ = false;
      open_ = true;
      comment_line_ = 0;
    }
    if (!too_long_) {
      if (joined_.size() + content.size() > max_bytes_) {
        too_long_ = true;
        on_too_long(segments_.empty() ? line_ : segments_[0].line);
      } else {
        segments_.push_back(Segment{static_cast<std::uint32_t>(joined_.size()), line_, 1});
        joined_.append(content);
        if (!comment.empty() && comments_.size() + comment.size() < max_bytes_) {
          if (comment_line_ == 0) {
            comment_line_ = line_;
            comment_column_ = comment_column;
          }
          if (!comments_.empty()) comments_ += ' ';
          comments_.append(comment);
        }
      }
    }
    if (continued) return;
    open_ = false;
    if (too_long_) return;
    Record r{joined_, comments_, comment_line_, comment_column_, &segments_};
    on_record(static_cast<const Record&>(r));
  }

  static std::string_view trim_comment(std::string_view s) noexcept {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
  }

  std::size_t max_bytes_;
  std::uint32_t line_ = 0;
  std::string carry_;  // a line cut by a piece boundary
  bool carry_too_long_ = false;
  std::vector<Segment> single_ = std::vector<Segment>(1);
  // A record continued over several lines.
  bool open_ = false;
  bool too_long_ = false;
  std::string joined_;
  std::string comments_;
  std::uint32_t comment_line_ = 0;
  std::uint32_t comment_column_ = 0;
  std::vector<Segment> segments_;
};

// ---- Fields ------------------------------------------------------------------------------------

[[nodiscard]] std::string_view trim(std::string_view s) noexcept;
// ASCII case-insensitive equality with an upper-case word.
[[nodiscard]] bool is_word(std::string_view text, std::string_view upper) noexcept;
// A number as APT writes it: optional sign, digits with an optional point, optional exponent
// (E or D). nullopt for anything else and for non-finite values.
[[nodiscard]] std::optional<double> parse_number(std::string_view text) noexcept;
// A plain decimal ([sign] digits [. digits], at most 15 significant digits) exactly as
// from_chars reads it, fast; nullopt for anything else (parse_number then takes the slow way).
[[nodiscard]] std::optional<double> fast_decimal(std::string_view text) noexcept;
// The fields of `args` when all are plain decimals and there are at most `max`: their count,
// values in `out`; 0 otherwise (the caller then splits and reports).
[[nodiscard]] std::size_t fast_numbers(std::string_view args, double* out,
                                       std::size_t max) noexcept;
// Splits `args` at commas into trimmed fields (reuses `out`).
void split_fields(std::string_view args, std::vector<std::string_view>& out);
// A number for a message: 4 decimals, or %g when that would be long (any finite double fits).
[[nodiscard]] std::string format_number(double value);
// A quoted text ('...' or "...") without its quotes; other text trimmed.
[[nodiscard]] std::string_view unquote(std::string_view text) noexcept;

}  // namespace ncpost::cls::detail
