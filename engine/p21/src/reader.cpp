#include "ncpost/p21/reader.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <optional>
#include <thread>

#include "cut_finder.hpp"
#include "lexer.hpp"
#include "ncpost/p21/stream_reader.hpp"
#include "ncpost/parallel/pieces.hpp"

namespace ncpost::p21 {
namespace {

using detail::Lexer;
using detail::Tok;
using detail::Token;
using diag::Code;

constexpr std::uint32_t kMaxParameters = 0x0FFFFFFFu;  // what a Value's count can hold

std::string describe(const Token& t, std::string_view text) {
  switch (t.kind) {
    case Tok::Eof:
      return "end of file";
    case Tok::Keyword:
      return "keyword '" + std::string(text.substr(t.offset, t.length)) + "'";
    case Tok::InstanceName:
      return "instance name '#" + std::to_string(detail::instance_id(text, t)) + "'";
    case Tok::ConstantName:
      return "constant name";
    case Tok::ValueName:
      return "value instance name";
    case Tok::Integer:
      return "integer";
    case Tok::Real:
      return "real";
    case Tok::String:
      return "string";
    case Tok::Binary:
      return "binary";
    case Tok::Enumeration:
      return "enumeration";
    case Tok::Resource:
      return "resource name";
    case Tok::LParen:
      return "'('";
    case Tok::RParen:
      return "')'";
    case Tok::Comma:
      return "','";
    case Tok::Equals:
      return "'='";
    case Tok::Semicolon:
      return "';'";
    case Tok::Dollar:
      return "'$'";
    case Tok::Star:
      return "'*'";
    case Tok::LBrace:
      return "'{'";
    case Tok::RBrace:
      return "'}'";
    case Tok::Colon:
      return "':'";
    case Tok::Magic:
      return "'ISO-10303-21'";
    case Tok::EndMagic:
      return "'END-ISO-10303-21'";
    case Tok::Error:
      return "malformed token";
  }
  return "token";
}

// Where a parameter list ended: normally at its ')'; otherwise the caller resynchronises.
enum class ListEnd : std::uint8_t { Closed, Broken };

class Parser {
 public:
  // `text` is the whole file's extent (slices are taken from it); only its first `available`
  // bytes may be read until extend() says more arrived, and `final` says that they are all.
  Parser(ModelBuilder& builder, std::string_view text, std::size_t available, bool final,
         diag::DiagnosticList& diagnostics, const ReadOptions& options)
      : builder_(builder),
        text_(text),
        lexer_(text.substr(0, available), diagnostics),
        diagnostics_(diagnostics),
        options_(options),
        final_(final) {
    advance();
  }

  // A piece from the middle of a DATA section: the instances in [from, available) of `text`,
  // read into a builder of its own (see read_pieces()).
  struct DataPiece {};
  Parser(DataPiece, ModelBuilder& builder, std::string_view text, std::size_t from,
         std::size_t available, diag::DiagnosticList& diagnostics, const ReadOptions& options)
      : builder_(builder),
        text_(text),
        lexer_(text.substr(0, available), diagnostics),
        diagnostics_(diagnostics),
        options_(options),
        final_(false) {
    lexer_.jump(from, available);
    stage_ = Stage::Data;
    seen_data_ = true;
    seen_header_ = true;  // the piece's file had one; the reader of its start checks that
    advance();
  }

  // Reads on. False: it stopped where the available text ends, at an instance or section
  // boundary, and extend() lets it go on; true: the file has been read to its end.
  bool run();
  // The first `available` bytes of `text` (which may have moved) can be read; `final`: all.
  void extend(std::string_view text, std::size_t available, bool final) {
    text_ = text;
    lexer_.extend(text.data(), available);
    final_ = final;
    // The end of the text that was available gave Tok::Eof; lex what follows it now.
    if (current_.kind == Tok::Eof && !has_peeked_) current_ = lexer_.next();
  }
  // Whether run() stopped cleanly at the end of the available text, so extend() may follow.
  [[nodiscard]] bool suspended() const { return suspended_ && !has_peeked_; }
  // Suspended between two instances of a DATA section.
  [[nodiscard]] bool suspended_in_data() const { return suspended() && stage_ == Stage::Data; }
  // When suspended_in_data(): the instances up to `offset` were read by another parser (and
  // appended to the builder), so this one goes on from there. extend() makes more available.
  void resume_at(std::size_t offset) {
    lexer_.jump(offset, offset);
    current_ = lexer_.next();  // Tok::Eof: nothing past `offset` is available yet
  }
  [[nodiscard]] bool cancelled() const { return cancelled_; }

 private:
  enum class Stage : std::uint8_t { Magic, Sections, Header, Data, End, Done };

  // ---- tokens ----
  void advance() {
    previous_end_ = current_.offset + current_.length;
    if (has_peeked_) {
      current_ = peeked_;
      has_peeked_ = false;
    } else {
      current_ = lexer_.next();
    }
    poll_cancel();
  }
  // A look at the flag every few thousand tokens costs nothing measurable and stops even one
  // enormous instance within microseconds.
  void poll_cancel() {
    if (options_.cancel == nullptr || --until_cancel_poll_ != 0) return;
    until_cancel_poll_ = kCancelPollTokens;
    if (!options_.cancel->load(std::memory_order_relaxed)) return;
    cancelled_ = true;
    lexer_.cut();
    has_peeked_ = false;
    current_ = lexer_.next();
  }
  const Token& peek() {
    if (!has_peeked_) {
      peeked_ = lexer_.next();
      has_peeked_ = true;
    }
    return peeked_;
  }
  [[nodiscard]] std::string_view slice(const Token& t) const {
    return text_.substr(t.offset, t.length);
  }
  [[nodiscard]] bool at_keyword(std::string_view word) const {
    return current_.kind == Tok::Keyword && slice(current_) == word;
  }
  [[nodiscard]] bool stopped() const { return diagnostics_.full() || cancelled_; }
  // At the end of the text that has arrived so far (not the file's end).
  [[nodiscard]] bool at_window_end() const { return current_.kind == Tok::Eof && !final_; }
  bool suspend() {
    suspended_ = true;
    return false;
  }

  void error(Code code, const Token& at, std::string message) {
    error_at(code, at.start, std::move(message));
  }
  void error_at(Code code, std::uint32_t offset, std::string message) {
    const auto pos = lexer_.position(offset);
    diagnostics_.add(code, pos.line, pos.column, std::move(message));
  }
  void unexpected(const Token& at, std::string_view expected) {
    if (at.kind == Tok::Error) return;  // the lexer has reported it
    error(Code::P21UnexpectedToken, at,
          "expected " + std::string(expected) + ", found " + describe(at, text_));
  }
  bool expect_semicolon(std::string_view after);

  // Skips the rest of a broken instance: up to and including the next ';', or up to the next
  // `#n =` or `ENDSEC;`, whichever comes first. Each token is looked at once: linear.
  void resynchronise();

  // ---- sections ----
  void begin_header_section();
  // False: suspended at the end of the available text inside the section.
  bool parse_header_entities();
  void parse_anchor_section();
  void parse_reference_section();
  void begin_data_section();
  // False: suspended at the end of the available text inside the section.
  bool parse_data_instances();
  void parse_instance();
  void end_of_file();
  void check_header_order(std::uint32_t first_header);

  // Parses the parameters after a '(' up to its ')', into the arena. On success `first` and
  // `count` describe the top-level parameters.
  ListEnd parse_parameters(std::uint32_t& first, std::uint32_t& count);
  std::optional<Value> simple_value(const Token& t);

  // Entity names repeat on almost every line, so a small direct-mapped cache of exact spellings
  // saves the case-insensitive hash look-up for nearly all of them.
  KeywordId intern(const Token& t) {
    const std::string_view name = slice(t);
    const std::size_t h = (name.size() * 31u + static_cast<unsigned char>(name.front()) * 7u +
                           static_cast<unsigned char>(name.back()) +
                           static_cast<unsigned char>(name[name.size() / 2]) * 131u) &
                          (kKeywordCacheSize - 1);
    KeywordCacheEntry& entry = keyword_cache_[h];
    if (entry.length == name.size() && entry.length != 0 &&
        std::memcmp(text_.data() + entry.offset, name.data(), name.size()) == 0)
      return entry.id;
    const KeywordId id = builder_.intern(name);
    entry = {t.offset, t.length, id};
    return id;
  }
  struct KeywordCacheEntry {
    std::uint32_t offset = 0;
    std::uint32_t length = 0;
    KeywordId id = 0;
  };
  static constexpr std::size_t kKeywordCacheSize = 512;
  std::array<KeywordCacheEntry, kKeywordCacheSize> keyword_cache_{};

  ModelBuilder& builder_;
  std::string_view text_;
  Lexer lexer_;
  diag::DiagnosticList& diagnostics_;
  const ReadOptions& options_;

  Token current_;
  Token peeked_;
  bool has_peeked_ = false;
  std::uint32_t previous_end_ = 0;  // just past the previous token, for "missing ';'"

  bool final_ = true;
  Stage stage_ = Stage::Magic;
  bool suspended_ = false;
  bool seen_data_ = false;
  bool seen_header_ = false;        // or its absence reported
  DataSection section_;             // the DATA section being read
  std::uint32_t first_header_ = 0;  // of the HEADER section being read
  static constexpr std::uint32_t kCancelPollTokens = 4096;
  std::uint32_t until_cancel_poll_ = kCancelPollTokens;
  bool cancelled_ = false;

  struct Frame {
    std::uint32_t stack_base;  // where this list's items start on the scratch stack
    KeywordId keyword;         // typed parameter keyword, or kListFrame
  };
  static constexpr KeywordId kListFrame = std::numeric_limits<KeywordId>::max();
  std::vector<Value> stack_;  // scratch: values of the lists being parsed
  std::vector<Frame> frames_;
};

bool Parser::expect_semicolon(std::string_view after) {
  if (current_.kind == Tok::Semicolon) {
    advance();
    return true;
  }
  if (current_.kind == Tok::RParen) {
    error(Code::P21UnbalancedParens, current_,
          "')' closes a parenthesis that was never opened in " + std::string(after));
    resynchronise();
    return false;
  }
  // A forgotten ';' before the next instance or section: report it and go on from there.
  error_at(Code::P21MissingSemicolon, previous_end_, "missing ';' after " + std::string(after));
  const bool next_starts_something =
      (current_.kind == Tok::InstanceName && peek().kind == Tok::Equals) ||
      current_.kind == Tok::Keyword || current_.kind == Tok::EndMagic;
  if (!next_starts_something) resynchronise();
  return false;
}

void Parser::resynchronise() {
  lexer_.set_quiet(true);
  while (current_.kind != Tok::Eof && current_.kind != Tok::EndMagic) {
    if (current_.kind == Tok::Semicolon) {
      // Speak again before the next token is lexed: errors after the ';' are new errors.
      lexer_.set_quiet(false);
      advance();
      return;
    }
    if (current_.kind == Tok::InstanceName && peek().kind == Tok::Equals) break;
    if (at_keyword("ENDSEC") && peek().kind == Tok::Semicolon) break;
    advance();
  }
  lexer_.set_quiet(false);
}

std::optional<Value> Parser::simple_value(const Token& t) {
  switch (t.kind) {
    case Tok::Dollar:
      return Value::omitted();
    case Tok::Star:
      return Value::derived();
    case Tok::Integer:
      return Value::slice(ValueKind::Integer, t.offset, t.length);
    case Tok::Real:
      return Value::slice(ValueKind::Real, t.offset, t.length);
    case Tok::String:
      return Value::slice(ValueKind::String, t.offset, t.length, t.needs_decoding);
    case Tok::Enumeration:
      return Value::slice(ValueKind::Enumeration, t.offset, t.length);
    case Tok::Binary:
      return Value::slice(ValueKind::Binary, t.offset, t.length);
    case Tok::InstanceName:
      return Value::reference(detail::instance_id(text_, t));
    case Tok::ConstantName:
      return Value::slice(ValueKind::ConstantName, t.offset, t.length);
    case Tok::ValueName:
      return Value::slice(ValueKind::ValueName, t.offset, t.length);
    case Tok::Resource:
      return Value::slice(ValueKind::Resource, t.offset, t.length);
    case Tok::Error:
      // A malformed literal whose extent is sound: it was reported; `$` stands in so that the
      // rest of the instance is still checked.
      if (t.recoverable) return Value::omitted();
      return std::nullopt;
    default:
      return std::nullopt;
  }
}

ListEnd Parser::parse_parameters(std::uint32_t& first, std::uint32_t& count) {
  // An explicit stack instead of recursion: nesting depth is data, and data may be hostile.
  frames_.clear();
  stack_.clear();
  frames_.push_back({static_cast<std::uint32_t>(stack_.size()), kListFrame});
  bool expect_value = true;  // otherwise expect ',' or ')'
  bool list_just_opened = true;
  std::uint32_t depth_seen = 1;

  const auto close_frame = [&]() -> bool {
    const Frame frame = frames_.back();
    frames_.pop_back();
    const auto n = static_cast<std::uint32_t>(stack_.size()) - frame.stack_base;
    if (n > kMaxParameters) {
      error(Code::P21TooManyParameters, current_, "more parameters than supported in one list");
      return false;
    }
    const std::uint32_t at =
        builder_.push_values(std::span<const Value>(stack_.data() + frame.stack_base, n));
    stack_.resize(frame.stack_base);
    if (frames_.empty()) {
      first = at;
      count = n;
      return true;
    }
    stack_.push_back(frame.keyword == kListFrame ? Value::list(at, n)
                                                 : Value::typed(frame.keyword, at));
    return true;
  };

  for (;;) {
    if (expect_value) {
      const Token t = current_;
      if (auto v = simple_value(t)) {
        stack_.push_back(*v);
        advance();
        expect_value = false;
        continue;
      }
      switch (t.kind) {
        case Tok::LParen:
        case Tok::Keyword: {
          KeywordId keyword = kListFrame;
          if (t.kind == Tok::Keyword) {
            advance();
            if (current_.kind != Tok::LParen) {
              unexpected(current_, "'(' after the type name of a typed parameter");
              return ListEnd::Broken;
            }
            keyword = intern(t);
          }
          if (frames_.size() >= options_.max_list_depth) {
            error(Code::P21NestingTooDeep, current_,
                  "lists nested deeper than " + std::to_string(options_.max_list_depth));
            return ListEnd::Broken;
          }
          frames_.push_back({static_cast<std::uint32_t>(stack_.size()), keyword});
          depth_seen = std::max(depth_seen, static_cast<std::uint32_t>(frames_.size()));
          advance();
          list_just_opened = keyword == kListFrame;  // a typed parameter needs its one value
          continue;
        }
        case Tok::RParen:
          if (list_just_opened) {  // empty list
            advance();
            if (!close_frame()) return ListEnd::Broken;
            if (frames_.empty()) {
              builder_.note_depth(depth_seen);
              return ListEnd::Closed;
            }
            expect_value = false;
            list_just_opened = false;
            continue;
          }
          [[fallthrough]];
        case Tok::Comma:
          // `(,#12,)`: an empty parameter. Report it, let `$` stand in, and go on.
          error(Code::P21EmptyParameter, t, "empty parameter; write $ for an unset value");
          stack_.push_back(Value::omitted());
          expect_value = false;
          list_just_opened = false;
          continue;
        case Tok::Semicolon:
          error(Code::P21UnbalancedParens, t,
                "';' before ')' closes " + std::to_string(frames_.size()) + " open parenthes" +
                    (frames_.size() == 1 ? "is" : "es"));
          return ListEnd::Broken;
        case Tok::Eof:
          error(Code::P21UnbalancedParens, t, "file ends inside a parameter list");
          return ListEnd::Broken;
        default:
          unexpected(t, "a parameter");
          return ListEnd::Broken;
      }
    }
    list_just_opened = false;
    switch (current_.kind) {
      case Tok::Comma:
        if (frames_.back().keyword != kListFrame) {
          unexpected(current_, "')' closing a typed parameter, which has exactly one value");
          return ListEnd::Broken;
        }
        advance();
        expect_value = true;
        continue;
      case Tok::RParen:
        advance();
        if (!close_frame()) return ListEnd::Broken;
        if (frames_.empty()) {
          builder_.note_depth(depth_seen);
          return ListEnd::Closed;
        }
        continue;
      case Tok::Semicolon:
        error(Code::P21UnbalancedParens, current_,
              "';' before ')' closes " + std::to_string(frames_.size()) + " open parenthes" +
                  (frames_.size() == 1 ? "is" : "es"));
        return ListEnd::Broken;
      case Tok::Eof:
        error(Code::P21UnbalancedParens, current_, "file ends inside a parameter list");
        return ListEnd::Broken;
      default:
        unexpected(current_, "',' or ')'");
        return ListEnd::Broken;
    }
  }
}

bool Parser::run() {
  suspended_ = false;
  for (;;) {
    switch (stage_) {
      case Stage::Magic:
        if (current_.kind != Tok::Magic) {
          error(Code::P21MissingMagic, current_,
                "the file must start with 'ISO-10303-21;', found " + describe(current_, text_));
          // Go on if a HEADER follows anyway: more can be said about the file that way.
          while (current_.kind != Tok::Eof && !at_keyword("HEADER") && !at_keyword("DATA"))
            advance();
        } else {
          advance();
          expect_semicolon("'ISO-10303-21'");
        }
        stage_ = Stage::Sections;
        continue;
      case Stage::Sections:
        if (stopped()) {
          stage_ = Stage::End;
          continue;
        }
        if (at_window_end()) return suspend();
        if (current_.kind == Tok::Eof) {
          error(Code::P21MissingEnd, current_, "the file ends without 'END-ISO-10303-21;'");
          stage_ = Stage::End;
          continue;
        }
        if (current_.kind == Tok::EndMagic) {
          // What follows the end (signatures, stray content) is read once all of it is there.
          if (!final_) return suspend();
          if (!seen_header_) {
            error(Code::P21MissingHeader, current_,
                  "the file ends without a HEADER section: expected 'HEADER;' here");
            seen_header_ = true;
          }
          end_of_file();
          stage_ = Stage::End;
          continue;
        }
        if (current_.kind == Tok::Keyword) {
          const std::string_view word = slice(current_);
          if (word != "HEADER" && !seen_header_) {
            // ISO 10303-21 §8: the HEADER section comes first; without it the file's schema,
            // and so the meaning of every instance, is unknown.
            error(Code::P21MissingHeader, current_,
                  "the HEADER section must come before " + std::string(word) +
                      ": expected 'HEADER;' here");
            seen_header_ = true;
          }
          if (word == "HEADER") {
            seen_header_ = true;
            begin_header_section();
            stage_ = Stage::Header;
            continue;
          }
          if (word == "ANCHOR") {
            parse_anchor_section();
            continue;
          }
          if (word == "REFERENCE") {
            parse_reference_section();
            continue;
          }
          if (word == "DATA") {
            seen_data_ = true;
            begin_data_section();
            stage_ = Stage::Data;
            continue;
          }
        }
        unexpected(current_, "a section (HEADER, ANCHOR, REFERENCE, DATA) or 'END-ISO-10303-21;'");
        advance();
        resynchronise();
        continue;
      case Stage::Header:
        if (!parse_header_entities()) return suspend();
        stage_ = Stage::Sections;
        continue;
      case Stage::Data:
        if (!parse_data_instances()) return suspend();
        section_.end_instance = builder_.instance_count();
        builder_.add_section(section_);
        stage_ = Stage::Sections;
        continue;
      case Stage::End:
        if (cancelled_) {
          stage_ = Stage::Done;
          continue;
        }
        if (stopped())
          error_at(Code::P21TooManyErrors, current_.start,
                   "stopped after " + std::to_string(options_.max_errors) + " errors");
        if (!seen_data_ && !stopped())
          diagnostics_.add(Code::P21NoData, 1, 1, "the file has no DATA section");
        stage_ = Stage::Done;
        continue;
      case Stage::Done:
        return true;
    }
  }
}

void Parser::end_of_file() {
  advance();
  expect_semicolon("'END-ISO-10303-21'");
  // Ed.3 signatures follow the end; their base64 content is not tokens.
  while (at_keyword("SIGNATURE")) {
    error(Code::P21SectionSkipped, current_, "SIGNATURE section skipped; it is not verified");
    lexer_.skip_raw_past("ENDSEC;");
    has_peeked_ = false;
    advance();
  }
  if (current_.kind != Tok::Eof)
    error(Code::P21TrailingContent, current_, "content after 'END-ISO-10303-21;' is ignored");
}

void Parser::check_header_order(std::uint32_t first_header) {
  static constexpr std::array<std::string_view, 3> kRequired = {"FILE_DESCRIPTION", "FILE_NAME",
                                                                "FILE_SCHEMA"};
  const auto& model = builder_.model();
  const auto header = model.header().subspan(first_header);
  for (std::size_t i = 0; i < kRequired.size(); ++i) {
    const bool in_place = i < header.size() && model.type_name(header[i]) == kRequired[i];
    if (in_place) continue;
    const bool present = model.header_entity(kRequired[i]) != nullptr;
    error_at(Code::P21HeaderEntity, current_.start,
             std::string(kRequired[i]) + (present ? " is out of order: the header must start with "
                                                    "FILE_DESCRIPTION, FILE_NAME, FILE_SCHEMA"
                                                  : " is missing from the header"));
  }
}

void Parser::begin_header_section() {
  advance();  // HEADER
  expect_semicolon("'HEADER'");
  first_header_ = static_cast<std::uint32_t>(builder_.model().header().size());
}

bool Parser::parse_header_entities() {
  while (!stopped()) {
    if (at_keyword("ENDSEC")) {
      check_header_order(first_header_);
      advance();
      expect_semicolon("'ENDSEC'");
      return true;
    }
    if (current_.kind == Tok::Keyword) {
      const Token keyword = current_;
      const std::uint32_t values_before = builder_.value_count();
      advance();
      if (current_.kind != Tok::LParen) {
        unexpected(current_, "'(' after header entity name");
        resynchronise();
        continue;
      }
      advance();
      Instance entity;
      entity.offset = keyword.start;
      entity.keyword = builder_.intern(slice(keyword));
      if (parse_parameters(entity.first, entity.count) == ListEnd::Broken) {
        builder_.truncate_values(values_before);
        resynchronise();
        continue;
      }
      builder_.add_header(entity);
      expect_semicolon(std::string(slice(keyword)));
      continue;
    }
    if (at_window_end()) return false;
    if (current_.kind == Tok::Eof || current_.kind == Tok::EndMagic || at_keyword("DATA")) {
      error(Code::P21MissingEndsec, current_, "HEADER section is not closed by 'ENDSEC;'");
      return true;
    }
    unexpected(current_, "a header entity or 'ENDSEC;'");
    advance();
    resynchronise();
  }
  return true;
}

void Parser::parse_anchor_section() {
  advance();  // ANCHOR
  expect_semicolon("'ANCHOR'");
  while (!stopped()) {
    if (at_keyword("ENDSEC")) {
      advance();
      expect_semicolon("'ENDSEC'");
      return;
    }
    if (current_.kind == Tok::Eof || current_.kind == Tok::EndMagic) {
      error(Code::P21MissingEndsec, current_, "ANCHOR section is not closed by 'ENDSEC;'");
      return;
    }
    if (current_.kind != Tok::Resource) {
      unexpected(current_, "an anchor name '<name>'");
      advance();
      resynchronise();
      continue;
    }
    Anchor anchor;
    anchor.name_offset = current_.offset;
    anchor.name_length = current_.length;
    anchor.offset = current_.start;
    advance();
    if (current_.kind != Tok::Equals) {
      unexpected(current_, "'=' after the anchor name");
      resynchronise();
      continue;
    }
    advance();
    if (auto v = simple_value(current_)) {
      anchor.item = *v;
      advance();
    } else if (current_.kind == Tok::LParen) {
      advance();
      std::uint32_t first = 0;
      std::uint32_t count = 0;
      if (parse_parameters(first, count) == ListEnd::Broken) {
        resynchronise();
        continue;
      }
      anchor.item = Value::list(first, count);
    } else {
      unexpected(current_, "an anchor item");
      resynchronise();
      continue;
    }
    if (current_.kind == Tok::LBrace) {
      error(Code::P21SectionSkipped, current_, "anchor tags are skipped");
      while (current_.kind != Tok::Semicolon && current_.kind != Tok::Eof) advance();
    }
    builder_.add_anchor(anchor);
    expect_semicolon("an anchor");
  }
}

void Parser::parse_reference_section() {
  advance();  // REFERENCE
  expect_semicolon("'REFERENCE'");
  while (!stopped()) {
    if (at_keyword("ENDSEC")) {
      advance();
      expect_semicolon("'ENDSEC'");
      return;
    }
    if (current_.kind == Tok::Eof || current_.kind == Tok::EndMagic) {
      error(Code::P21MissingEndsec, current_, "REFERENCE section is not closed by 'ENDSEC;'");
      return;
    }
    const Token name = current_;
    if (name.kind != Tok::InstanceName) {
      unexpected(name, "'#n = <uri>;' in the REFERENCE section");
      advance();
      resynchronise();
      continue;
    }
    advance();
    if (current_.kind != Tok::Equals) {
      unexpected(current_, "'='");
      resynchronise();
      continue;
    }
    advance();
    if (current_.kind != Tok::Resource) {
      unexpected(current_, "a resource '<uri>'");
      resynchronise();
      continue;
    }
    // An external instance: it takes part in reference resolution like a local one.
    const Value uri = Value::slice(ValueKind::Resource, current_.offset, current_.length);
    Instance external;
    external.id = detail::instance_id(text_, name);
    external.offset = name.start;
    external.keyword = Model::kExternalKeyword;
    external.first = builder_.push_values(std::span<const Value>(&uri, 1));
    external.count = 1;
    builder_.add_instance(external);
    advance();
    expect_semicolon("a reference");
  }
}

void Parser::begin_data_section() {
  section_ = DataSection{};
  section_.offset = current_.start;
  advance();  // DATA
  if (current_.kind == Tok::LParen) {
    advance();
    if (parse_parameters(section_.first_param, section_.param_count) == ListEnd::Broken)
      resynchronise();
  }
  expect_semicolon("'DATA'");
  section_.first_instance = builder_.instance_count();
}

bool Parser::parse_data_instances() {
  while (!stopped()) {
    if (current_.kind == Tok::InstanceName) {
      parse_instance();
      continue;
    }
    if (at_keyword("ENDSEC")) {
      advance();
      expect_semicolon("'ENDSEC'");
      break;
    }
    if (at_window_end()) return false;
    if (current_.kind == Tok::Eof || current_.kind == Tok::EndMagic ||
        (current_.kind == Tok::Keyword && peek().kind == Tok::Semicolon)) {
      error(Code::P21MissingEndsec, current_, "DATA section is not closed by 'ENDSEC;'");
      break;
    }
    unexpected(current_, "an instance '#n = ...;' or 'ENDSEC;'");
    advance();
    resynchronise();
  }
  return true;
}

void Parser::parse_instance() {
  const Token name = current_;
  advance();
  if (current_.kind != Tok::Equals) {
    unexpected(current_, "'=' after " + describe(name, text_));
    resynchronise();
    return;
  }
  advance();
  Instance instance;
  instance.id = detail::instance_id(text_, name);
  instance.offset = name.start;
  // A broken instance leaves nothing behind in the arena.
  const std::uint32_t values_before = builder_.value_count();
  const auto drop = [&] {
    builder_.truncate_values(values_before);
    resynchronise();
  };
  // Built only when a message needs it: this runs once per instance.
  const auto what = [&] { return "instance #" + std::to_string(instance.id); };

  if (current_.kind == Tok::Keyword) {
    instance.keyword = intern(current_);
    advance();
    if (current_.kind != Tok::LParen) {
      unexpected(current_, "'(' after the entity name of " + what());
      drop();
      return;
    }
    advance();
    if (parse_parameters(instance.first, instance.count) == ListEnd::Broken) {
      drop();
      return;
    }
  } else if (current_.kind == Tok::LParen) {
    // Complex instance: partial records, each kept as a typed value NAME((params)).
    advance();
    instance.keyword = Model::kComplexKeyword;
    std::vector<Value> records;
    while (current_.kind == Tok::Keyword) {
      const KeywordId record = intern(current_);
      advance();
      if (current_.kind != Tok::LParen) {
        unexpected(current_, "'(' after a partial record name in " + what());
        drop();
        return;
      }
      advance();
      std::uint32_t first = 0;
      std::uint32_t count = 0;
      if (parse_parameters(first, count) == ListEnd::Broken) {
        drop();
        return;
      }
      const Value list = Value::list(first, count);
      records.push_back(
          Value::typed(record, builder_.push_values(std::span<const Value>(&list, 1))));
    }
    if (current_.kind != Tok::RParen) {
      unexpected(current_, "a partial record name or ')' in complex " + what());
      drop();
      return;
    }
    if (records.empty()) {
      error(Code::P21EmptyComplex, name, "complex " + what() + " has no partial records");
      advance();
      drop();
      return;
    }
    advance();
    instance.first = builder_.push_values(records);
    instance.count = static_cast<std::uint32_t>(records.size());
  } else {
    unexpected(current_, "an entity name or '(' for " + what());
    resynchronise();
    return;
  }
  builder_.add_instance(instance);
  if (current_.kind == Tok::Semicolon)
    advance();
  else
    expect_semicolon(what());
}

ReadResult cancelled_result() {
  ReadResult r;
  r.cancelled = true;
  return r;
}

[[nodiscard]] bool cancel_requested(const ReadOptions& options) {
  return options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed);
}

// After the scan: ids, duplicates and references. False when cancelled.
bool resolve(ModelBuilder& builder, diag::DiagnosticList& diagnostics, const ReadOptions& options) {
  const auto duplicates = builder.build_indexes();
  const Model& model = builder.model();
  std::optional<LineIndex> lines;
  const auto position = [&](std::uint32_t offset) {
    if (!lines) lines.emplace(model.text());
    return lines->at(offset);
  };
  for (const auto& d : duplicates) {
    const Instance& dup = model.instances()[d.duplicate_index];
    const Instance& kept = model.instances()[d.first_index];
    const auto at = position(dup.offset);
    const auto first_at = position(kept.offset);
    diagnostics.add(Code::P21DuplicateId, at.line, at.column,
                    "#" + std::to_string(dup.id) + " is defined again (first at line " +
                        std::to_string(first_at.line) + "); this one is ignored");
  }
  if (!options.check_references) return true;

  // Walk each instance's values with an explicit stack; depth is bounded by max_list_depth.
  struct Pending {
    std::span<const Value> values;
    std::size_t next;
  };
  std::vector<Pending> work;
  const auto check_instance = [&](const Instance& inst) {
    const auto top = model.params(inst);
    const bool complex = model.is_complex(inst);
    for (std::size_t attribute = 0; attribute < top.size(); ++attribute) {
      work.clear();
      work.push_back({top.subspan(attribute, 1), 0});
      std::string_view record_name;
      if (complex) record_name = model.keyword(top[attribute].keyword_id());
      while (!work.empty() && !diagnostics.full()) {
        Pending& p = work.back();
        if (p.next == p.values.size()) {
          work.pop_back();
          continue;
        }
        const Value v = p.values[p.next++];
        if (v.is_list()) {
          work.push_back({model.items(v), 0});
        } else if (v.kind() == ValueKind::Typed) {
          work.push_back({model.all_values().subspan(v.child(), 1), 0});
        } else if (v.is_reference() && model.find(v.id()) == nullptr) {
          const auto at = position(inst.offset);
          std::string where = complex ? "#" + std::to_string(inst.id) + " (partial record " +
                                            std::string(record_name) + ")"
                                      : "#" + std::to_string(inst.id) + " attribute " +
                                            std::to_string(attribute + 1);
          diagnostics.add(Code::P21DanglingReference, at.line, at.column,
                          "#" + std::to_string(v.id()) + " used by " + where + " is not defined");
        }
      }
    }
  };
  constexpr std::size_t kCancelPollInstances = 4096;
  std::size_t until_poll = kCancelPollInstances;
  for (const auto& inst : model.instances()) {
    if (diagnostics.full()) break;
    if (--until_poll == 0) {
      until_poll = kCancelPollInstances;
      if (cancel_requested(options)) return false;
    }
    if (inst.keyword != Model::kExternalKeyword) check_instance(inst);
  }
  for (const auto& anchor : model.anchors()) {
    if (anchor.item.is_reference() && model.find(anchor.item.id()) == nullptr) {
      const auto at = position(anchor.offset);
      diagnostics.add(Code::P21DanglingReference, at.line, at.column,
                      "#" + std::to_string(anchor.item.id()) + " used by anchor <" +
                          std::string(model.text().substr(anchor.name_offset, anchor.name_length)) +
                          "> is not defined");
    }
  }
  return true;
}

// ---- a large file in pieces ------------------------------------------------------------------

// Whether the line before the one starting at `line_start` ends an instance: its last byte other
// than blanks is ';'.
bool after_instance_end(std::string_view text, std::size_t line_start) {
  std::size_t i = line_start - 1;  // the '\n'
  while (i > 0 && (text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\r')) --i;
  return i > 0 && text[i - 1] == ';';
}

// Where a text may be cut for reading in pieces: the start of a line that begins an instance
// ('#') after a line that ended one (';'). Something inside a string or a comment can look like
// this; the piece before such a cut then ends in an open literal, which its parser reports, and
// the file is read again in one piece. So a bad cut costs time, never a different result.
std::size_t cut_at_or_after(std::string_view text, std::size_t from) {
  for (std::size_t at = text.find("\n#", from); at != std::string_view::npos;
       at = text.find("\n#", at + 1))
    if (after_instance_end(text, at + 1)) return at + 1;
  return std::string_view::npos;
}

std::size_t last_cut_after(std::string_view text, std::size_t after) {
  for (std::size_t at = text.rfind("\n#"); at != std::string_view::npos && at + 1 > after;
       at = at == 0 ? std::string_view::npos : text.rfind("\n#", at - 1))
    if (after_instance_end(text, at + 1)) return at + 1;
  return std::string_view::npos;
}

// The cuts for reading text[from, end) in pieces: piece 0 is [from, cuts[0]), piece i is
// [cuts[i - 1], cuts[i]), and the first parser reads from cuts.back() to the end (the last
// instances, ENDSEC and the rest). At least one piece per thread, each at least min_piece_bytes,
// and more pieces of at most max_piece_bytes when the text is long: a piece read apart is held
// twice while it is appended, so small pieces keep that extra memory small. Empty: not worth
// it, or no cut found.
std::vector<std::size_t> plan_cuts(std::string_view text, std::size_t from,
                                   const ReadOptions& options) {
  constexpr std::size_t kMaxPieces = 4096;
  const std::size_t length = text.size() - from;
  const std::size_t threads = parallel::max_pieces(options.helpers);
  const std::size_t by_size = length / std::max<std::size_t>(options.min_piece_bytes, 1);
  std::vector<std::size_t> cuts;
  if (threads < 2 || by_size < 2) return cuts;
  const std::size_t pieces =
      std::min(kMaxPieces, std::max(std::min(threads, by_size),
                                    length / std::max<std::size_t>(options.max_piece_bytes, 1)));
  for (std::size_t i = 1; i < pieces; ++i) {
    const std::size_t cut = cut_at_or_after(text, from + length / pieces * i);
    if (cut == std::string_view::npos) break;
    if (!cuts.empty() && cut <= cuts.back()) continue;
    cuts.push_back(cut);
  }
  if (cuts.empty()) return cuts;
  const std::size_t end = last_cut_after(text, cuts.back());
  if (end == std::string_view::npos) return {};
  cuts.push_back(end);
  return cuts;
}

// `main` has text[0, cuts[0]) available and reads it; the other pieces are read by whichever
// thread takes them (parallel::run_pieces). The reading thread reads a piece with `main` itself
// when `main` has read every piece before it; any other piece gets a parser and a model of its
// own, and the clean ones are then appended in order, `main` resuming after each. A piece with
// anything to report is left for `main` to read itself, so that diagnostics come out exactly as
// from one parser. 0: `main` did not end its part cleanly between two instances (a cut inside
// a literal, an error before the cut, a cancel), so the text must be read again in one piece.
// Otherwise `main` can go on from wherever it stands once extend() gives it the rest; the
// count is 1 + the pieces read apart and appended.
std::size_t read_pieces(Parser& main, ModelBuilder& builder, std::string_view text,
                        const std::vector<std::size_t>& cuts,
                        const diag::DiagnosticList& diagnostics, const ReadOptions& options) {
  struct Piece {
    std::unique_ptr<ModelBuilder> builder;
    bool clean = false;
  };
  std::vector<Piece> pieces(cuts.size());  // [0] is main's
  const auto reading_thread = std::this_thread::get_id();
  std::size_t read_by_main = 0;  // the reading thread's: main has read pieces [0, read_by_main)
  const auto read_piece = [&](std::size_t index) {
    if (std::this_thread::get_id() == reading_thread && index == read_by_main) {
      if (index > 0) {
        if (!main.suspended_in_data() || !diagnostics.items().empty()) return;  // no use now
        main.extend(text, cuts[index], false);
      }
      (void)main.run();
      ++read_by_main;
      return;
    }
    Piece& piece = pieces[index];
    const std::size_t from = cuts[index - 1];
    const std::size_t to = cuts[index];
    piece.builder =
        std::make_unique<ModelBuilder>(std::string{}, (to - from) / 2 + 16, (to - from) / 6 + 16);
    diag::DiagnosticList found(options.max_errors);
    Parser parser(Parser::DataPiece{}, *piece.builder, text, from, to, found, options);
    // Ending in a DATA section is not enough: it has to be the one the piece began in.
    piece.clean = !parser.run() && parser.suspended_in_data() && found.items().empty() &&
                  piece.builder->model().sections().empty();
    if (!piece.clean) piece.builder.reset();
  };
  parallel::run_pieces(cuts.size(), read_piece, options.helpers);
  if (!main.suspended_in_data() || !diagnostics.items().empty()) return 0;
  std::size_t appended = 0;
  for (std::size_t i = read_by_main; i < pieces.size() && pieces[i].clean; ++i, ++appended) {
    builder.append(std::move(*pieces[i].builder).finish());
    pieces[i].builder.reset();
    main.resume_at(cuts[i]);
  }
  return appended + 1;
}

}  // namespace

bool ReadResult::ok() const {
  return !cancelled && std::none_of(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
    return d.severity == diag::Severity::Error;
  });
}

namespace {

// Upper bounds: every value takes at least two bytes of text ("1,"), every instance six
// ("#1=A();"). Reserving them avoids any reallocation copy while reading.
std::unique_ptr<ModelBuilder> builder_for(std::string text, std::size_t size) {
  return std::make_unique<ModelBuilder>(std::move(text), size / 2 + 16, size / 6 + 16);
}

// The rest of the text, now all there, read by `parser` (and helpers), then the references.
ReadResult read_to_end(Parser& parser, ModelBuilder& builder, std::string text,
                       diag::DiagnosticList& diagnostics, const ReadOptions& options) {
  builder.set_text(std::move(text));
  const std::string_view whole = builder.text();
  parser.extend(whole, whole.size(), true);
  (void)parser.run();
  if (parser.cancelled() || !resolve(builder, diagnostics, options)) return cancelled_result();
  return {std::move(builder).finish(), std::move(diagnostics).take()};
}

ReadResult read_in_one_piece(std::string text, const ReadOptions& options) {
  diag::DiagnosticList diagnostics(options.max_errors);
  const std::size_t size = text.size();
  const auto builder = builder_for(std::move(text), size);
  Parser parser(*builder, builder->text(), size, true, diagnostics, options);
  (void)parser.run();
  if (parser.cancelled() || !resolve(*builder, diagnostics, options)) return cancelled_result();
  return {std::move(*builder).finish(), std::move(diagnostics).take()};
}

// `parser` has read what lies before `cuts.front()` (or before the end, when there are no cuts)
// into `builder`; the rest is read in the pieces that `cuts` plans, then to the end. When the
// pieces cannot be used, both are released before the whole text is read again in one piece,
// so that two models are never held at once.
ReadResult read_rest(std::unique_ptr<Parser>& parser, std::unique_ptr<ModelBuilder>& builder,
                     std::string text, const std::vector<std::size_t>& cuts,
                     diag::DiagnosticList& diagnostics, const ReadOptions& options) {
  std::size_t pieces = 1;
  if (!cuts.empty()) {
    parser->extend(text, cuts.front(), false);
    pieces = read_pieces(*parser, *builder, text, cuts, diagnostics, options);
    if (cancel_requested(options)) return cancelled_result();
    if (pieces == 0) {
      parser.reset();
      builder.reset();
      return read_in_one_piece(std::move(text), options);
    }
  }
  ReadResult result = read_to_end(*parser, *builder, std::move(text), diagnostics, options);
  if (!result.cancelled) result.pieces = pieces;
  return result;
}

}  // namespace

ReadResult read(std::string text, const ReadOptions& options) {
  if (text.size() >= std::numeric_limits<std::uint32_t>::max()) {
    diag::DiagnosticList diagnostics(options.max_errors);
    diagnostics.add(Code::P21FileTooLarge, 0, 0,
                    "input of " + std::to_string(text.size()) +
                        " bytes is larger than the reader's 4 GiB limit");
    return {Model{}, std::move(diagnostics).take()};
  }
  const auto cuts = plan_cuts(text, 0, options);
  if (cuts.empty()) return read_in_one_piece(std::move(text), options);
  diag::DiagnosticList diagnostics(options.max_errors);
  auto builder = builder_for(std::string{}, text.size());
  auto parser = std::make_unique<Parser>(*builder, text, 0, false, diagnostics, options);
  return read_rest(parser, builder, std::move(text), cuts, diagnostics, options);
}

// ---- StreamReader -----------------------------------------------------------------------------

struct StreamReader::Impl {
  Impl(std::size_t size_, const ReadOptions& options_)
      : options(options_),
        size(size_),
        diagnostics(options_.max_errors),
        builder(std::make_unique<ModelBuilder>(std::string{}, size_ / 2 + 16, size_ / 6 + 16)) {
    text.reserve(size);
    base = text.data();  // stable: appends stay within the reserved capacity
  }

  void give_up() {
    gave_up = true;
    parser.reset();
    builder.reset();
  }

  ReadOptions options;
  std::size_t size;
  std::string text;
  const char* base;
  diag::DiagnosticList diagnostics;
  std::unique_ptr<ModelBuilder> builder;
  std::unique_ptr<Parser> parser;
  detail::CutFinder cuts;
  std::size_t window = 0;  // bytes handed to the parser
  bool gave_up = false;
  bool finished = false;
};

StreamReader::StreamReader(std::size_t size, const ReadOptions& options)
    : impl_(std::make_unique<Impl>(size, options)) {
  // Too large for the reader's offsets: p21::read() reports it at the end.
  if (size >= std::numeric_limits<std::uint32_t>::max()) impl_->give_up();
}

StreamReader::~StreamReader() = default;

std::size_t StreamReader::size() const {
  return impl_->size;
}

bool StreamReader::append(std::string_view bytes) {
  Impl& m = *impl_;
  if (bytes.size() > m.size - m.text.size()) return false;
  m.text.append(bytes);
  return true;
}

std::size_t StreamReader::appended() const {
  return impl_->text.size();
}

std::string_view StreamReader::arrived(std::size_t available) const {
  return {impl_->base, available};
}

std::size_t StreamReader::read_through() const {
  return impl_->gave_up ? 0 : impl_->window;
}

bool StreamReader::gave_up() const {
  return impl_->gave_up;
}

void StreamReader::read_more(std::size_t available) {
  Impl& m = *impl_;
  if (m.gave_up || m.finished) return;
  m.cuts.scan(m.base, available);
  if (m.cuts.cut() <= m.window) return;
  m.window = m.cuts.cut();
  const std::string_view whole(m.base, m.size);
  if (!m.parser)
    m.parser =
        std::make_unique<Parser>(*m.builder, whole, m.window, false, m.diagnostics, m.options);
  else
    m.parser->extend(whole, m.window, false);
  const bool done = m.parser->run();
  // Reading the rest the ordinary way is what keeps the result independent of the pieces.
  if (done || !m.parser->suspended() || !m.diagnostics.items().empty()) m.give_up();
}

ReadResult StreamReader::finish() {
  Impl& m = *impl_;
  m.finished = true;
  if (cancel_requested(m.options)) return cancelled_result();
  if (m.gave_up || !m.parser) {
    m.parser.reset();
    m.builder.reset();
    return read(std::move(m.text), m.options);
  }
  // What has not been read while it arrived is read in pieces when it is large enough.
  const auto cuts = plan_cuts(m.text, m.window, m.options);
  return read_rest(m.parser, m.builder, std::move(m.text), cuts, m.diagnostics, m.options);
}

std::string StreamReader::take_text() {
  impl_->finished = true;
  impl_->give_up();
  return std::move(impl_->text);
}

LineIndex::LineIndex(std::string_view text) {
  line_starts_.push_back(0);
  const char* base = text.data();
  const char* p = base;
  const char* end = base + text.size();
  while (const void* hit = std::memchr(p, '\n', static_cast<std::size_t>(end - p))) {
    p = static_cast<const char*>(hit) + 1;
    line_starts_.push_back(static_cast<std::uint32_t>(p - base));
  }
}

LineIndex::Position LineIndex::at(std::uint32_t offset) const {
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const auto line = static_cast<std::uint32_t>(it - line_starts_.begin());
  return {line, offset - line_starts_[line - 1] + 1};
}

}  // namespace ncpost::p21
