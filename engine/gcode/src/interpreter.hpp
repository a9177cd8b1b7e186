#pragma once
// The driver of one read: lines in program order as control flow takes them (subprogram
// calls, loops, jumps, across the uploaded files), each line lexed, its statement or block
// read and evaluated, then handed to the converter. The statement forms of each family live
// in their own files: interpreter.cpp (LinuxCNC O-words, FANUC macro B and M98/M99/G65),
// sinumerik.cpp, klartext.cpp.
//
// Memory: the text is the caller's; the interpreter keeps one Line, one Block, the call and
// loop stacks (bounded by max_call_depth) and — only for files where a program jumps to a
// label or calls a subprogram — an index of that file's labels and subprogram starts.

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "block.hpp"
#include "converter.hpp"
#include "evaluator.hpp"
#include "lexer.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "parameters.hpp"
#include "report.hpp"

namespace ncpost::gcode::detail {

// Sees each block as it is read (the XML form). Values are after evaluation.
class BlockObserver {
 public:
  virtual ~BlockObserver() = default;
  virtual void begin_block(std::string_view file, std::uint32_t line, std::string_view raw) = 0;
  virtual void word(std::string_view name, std::string_view text, double value,
                    std::uint32_t column) = 0;
  virtual void comment(std::string_view text, std::uint32_t column) = 0;
  virtual void statement(std::string_view kind, std::string_view text) = 0;
  virtual void end_block() = 0;
};

struct Position {
  std::size_t source = 0;
  std::size_t offset = 0;  // of the line's start
  std::uint32_t line = 1;  // its number
};

[[nodiscard]] std::uint32_t long_word_initials(const Dialect& dialect) noexcept;

class Interpreter {
 public:
  Interpreter(std::string_view text, const Dialect& dialect, canon::Sink& sink,
              const ReadOptions& options, BlockObserver* observer);
  // Each diagnostic as it is added (the XML form places them in their block).
  void on_diagnostic(std::function<void(const diag::FileDiagnostic&)> listener) {
    report_.set_listener(std::move(listener));
  }
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  void run();

  [[nodiscard]] ReadResult result() &&;

 private:
  struct Source {
    std::string name;
    std::string_view text;
    // Built on first need: label → position (N numbers, Sinumerik labels, Heidenhain LBL), and
    // subprogram → position of its first line.
    std::optional<std::map<std::string, Position, std::less<>>> labels;
    std::optional<std::map<std::string, Position, std::less<>>> subprograms;
  };
  enum class LoopKind : std::uint8_t { While, Do, Repeat, For, Loop };
  struct Loop {
    std::string label;
    LoopKind kind = LoopKind::While;
    Position start;  // the line to go back to
    long long remaining = 0;
    // Sinumerik FOR: the counter and its end value.
    std::string counter;
    double counter_number = -1;
    double end = 0;
  };
  enum class FrameKind : std::uint8_t { Main, OWord, Fanuc, Macro, Sinumerik, Label };
  struct Frame {
    FrameKind kind = FrameKind::Main;
    std::string label;     // o-word name, program number, LBL
    Position back;         // where the caller continues
    Position start;        // the subprogram's first line (repeats start again here)
    long long repeat = 0;  // further runs after this one
    bool locals = false;   // pushed a parameter frame
    std::vector<Loop> loops;
    std::vector<std::optional<double>> args;  // a Sinumerik call's arguments, for its PROC
  };

  // ---- core (interpreter.cpp) ----
  bool next_line();  // reads, lexes; false at the end of everything
  void step_block();
  bool read_words(std::size_t pos, Block& block);
  bool read_word_value(std::size_t& pos, Value& value, bool& integer_literal, bool equals);
  bool apply_assignments(const Block& block);
  bool take_assignment(Block& block, Assignment a);
  bool assign(const Assignment& a);
  void execute_block(Block& block);
  void handle_comments(bool& stop);
  void do_flow(const FlowRequest& flow);
  bool call(std::size_t source, const Position& target, FrameKind kind, std::string label,
            long long repeat, bool locals);
  void return_from_call(std::optional<double> value, std::optional<std::string> label_to_go);
  [[nodiscard]] std::optional<Position> find_fanuc_program(double number, std::size_t& source);
  [[nodiscard]] std::optional<std::size_t> find_file(std::string_view name);
  [[nodiscard]] const Position* find_label(std::size_t source, std::string_view label);
  void index_labels(Source& s);
  void index_subprograms(Source& s);
  void jump(const Position& p);
  bool skip_to(const std::vector<std::string_view>& keywords, std::string_view label,
               std::string_view& found);
  bool evaluate_at(std::size_t& pos, Evaluator::Mode mode, Value& out);
  bool evaluate_condition(std::size_t& pos, bool& result);
  void report_eval_error();
  void warn_machine_reads();
  bool error(std::uint32_t column, diag::Code code, std::string message);
  void warn(std::uint32_t column, diag::Code code, std::string message);
  void end_program();
  [[nodiscard]] bool done_by_error() const;
  [[nodiscard]] std::uint32_t column(std::size_t pos) const { return line_->column(pos); }
  [[nodiscard]] Where where() const { return {sources_[position_.source].name, line_->number}; }
  [[nodiscard]] std::string_view text() const { return line_->text; }

  // LinuxCNC O-words.
  bool o_word_statement(std::size_t pos);
  bool read_o_label(std::string_view t, std::size_t& pos, std::string& label);
  // FANUC macro B.
  bool macro_statement(std::size_t pos, bool& handled);
  [[nodiscard]] bool starts_macro_statement(std::string_view t, std::size_t pos) const;

  // ---- Sinumerik (sinumerik.cpp) ----
  using Structure_ = std::uint8_t;
  bool sinumerik_statement(std::size_t pos, bool& handled);
  bool sinumerik_skip(Structure_ open, Structure_ close, Structure_ also);
  bool sinumerik_jump(std::string_view keyword, std::string_view label, std::uint32_t col);
  bool sinumerik_arguments(std::size_t& pos, std::vector<std::optional<double>>& out);
  bool sinumerik_cycle(const std::string& name, const std::vector<std::optional<double>>& args,
                       std::uint32_t col);
  bool sinumerik_call(std::string_view name, std::size_t pos, std::uint32_t col);
  bool sinumerik_set(const std::string& name, double number, Value v, std::uint32_t col);
  [[nodiscard]] bool is_keyword(std::string_view name) const;
  void run_modal_call(const Block& b);

  // ---- Heidenhain Klartext (klartext.cpp) ----
  void klartext_line();
  void klartext_cycle_call(std::uint32_t col);
  void klartext_fn(std::size_t pos);
  bool klartext_q_target(std::size_t& p, double& index);

  const Dialect& dialect_;
  const Lexing lexing_{dialect_};
  // Bit k: some multi-letter word of the dialect (Sinumerik CR, TURN) starts with letter 'A'+k,
  // so a word starting with it must be matched against them (most dialects have none).
  const std::uint32_t long_word_initials_ = long_word_initials(dialect_);
  const ReadOptions& options_;
  BlockObserver* observer_;
  Report report_;
  canon::Sink& sink_;
  Converter converter_;
  Parameters parameters_;
  Evaluator evaluator_;
  std::vector<Source> sources_;
  std::vector<Frame> frames_;
  LineCursor cursor_;
  Position position_;  // of the line in line_
  // Normalised lines by the source and offset they start at, direct-mapped: the lines of a
  // loop are lexed once, not on every pass. Lines longer than kCachedLineMax go to spare_line_
  // (as does a line that is not normalised, or is changed), so the cache stays small.
  static constexpr std::size_t kLineCacheSize = 64;
  static constexpr std::size_t kCachedLineMax = 512;
  struct CachedLine {
    std::size_t source = static_cast<std::size_t>(-1);
    std::size_t offset = 0;
    Line line;
  };
  std::array<CachedLine, kLineCacheSize> line_cache_;
  Line spare_line_;
  Line* line_ = &spare_line_;  // the current line
  // The line `raw` at position_ into line_, normalised (or from the cache).
  void load_line(std::string_view raw, std::uint32_t number);
  // line_ as a line of its own, to be changed without changing the cache.
  void detach_line();
  // line_: a line that is not read (too long, past the step limit), for its diagnostic.
  void set_unread_line(std::string_view raw, std::uint32_t number);
  Block block_;
  std::uint64_t steps_ = 0;
  bool done_ = false;
  bool cancelled_ = false;
  bool percent_seen_ = false;
  bool executed_any_ = false;  // a block other than titles and comments ran
  bool titled_ = false;        // the main program has an O title
  bool percent_end_ = false;   // a closing '%' ended the program
  std::vector<Comment> plain_comments_;
  // Sinumerik: a modal cycle call (MCALL) and the arguments of a call for its PROC.
  struct ModalCall {
    std::string name;
    std::vector<std::optional<double>> args;
    std::uint32_t column = 0;
  };
  std::optional<ModalCall> mcall_;
  std::string program_name_;
  std::string scratch_;
  struct KlartextState;
  std::unique_ptr<KlartextState> klartext_;
};

}  // namespace ncpost::gcode::detail
