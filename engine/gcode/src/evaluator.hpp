#pragma once
// Expressions, evaluated where they stand, before the block is checked (the papers' order):
// `X[1+2]`, `YSIN[30]`, `#[#110+1]`, `X [ - #6 / 2. ]`, Sinumerik `X=R1*2`, Heidenhain
// `Q1 = Q2 + SIN Q3`. Operators, their precedence and the functions come from the dialect.
//
// An operator-precedence (shunting-yard) evaluator with explicit stacks: nesting costs stack
// entries, never native recursion, and is bounded by ReadOptions::max_expression_depth.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/gcode/dialect.hpp"
#include "parameters.hpp"
#include "value.hpp"

namespace ncpost::gcode::detail {

struct EvalError {
  std::size_t pos = 0;  // index into the text where it went wrong
  diag::Code code = diag::Code::GcodeBadExpression;
  std::string message;
};

// A value only the machine knows was read (the caller warns once, naming it).
struct MachineRead {
  std::string name;
  double assumed = 0;
};

class Evaluator {
 public:
  Evaluator(const Dialect& dialect, Parameters& parameters, std::size_t max_depth);

  enum class Mode : std::uint8_t {
    Primary,      // one value: a number, a parameter, [..], a function: a word's value
    Full,         // a whole expression, to the end of what can continue it
    FullToSpace,  // a whole expression that a space at the outer level ends (X=R1+2 Y=..)
  };

  // Evaluates at text[pos] and advances pos past what it read. False on an error (error()).
  [[nodiscard]] bool evaluate(std::string_view text, std::size_t& pos, Mode mode, Value& out);

  [[nodiscard]] const EvalError& error() const noexcept { return error_; }
  // Machine values read since the last clear (the caller warns and clears).
  [[nodiscard]] std::vector<MachineRead>& machine_reads() noexcept { return machine_reads_; }

  // A number literal at text[pos] (digits with at most one point, no sign). Sets `integer`
  // when it has no decimal point. False when there is none.
  [[nodiscard]] static bool scan_number(std::string_view text, std::size_t& pos, double& out,
                                        bool& integer) noexcept;
  // Applies a binary operator (shared with statement forms such as Heidenhain FN 1..4).
  [[nodiscard]] bool binary(Operator op, const Value& a, const Value& b, Value& out);
  [[nodiscard]] bool function(Function fn, const Value* args, std::size_t count, Value& out);

 private:
  enum class OpKind : std::uint8_t { Binary, Unary, Open, Call };
  enum class UnaryOp : std::uint8_t { Neg, Pos, Hash, Not, Fn };
  struct Op {
    OpKind kind = OpKind::Binary;
    Operator binary = Operator::Add;
    UnaryOp unary = UnaryOp::Neg;
    Function fn = Function::Sin;
    int precedence = 0;
    int args = 1;               // Open of a call: values so far
    bool call_bracket = false;  // Open that belongs to the Call below it
    std::size_t pos = 0;
  };

  bool fail(std::size_t pos, diag::Code code, std::string message);
  bool reduce_one();
  bool reduce_while(int precedence);
  bool apply_unary(const Op& op);
  bool read_parameter_name(std::string_view text, std::size_t& pos, std::string& name);
  bool read_operand(std::string_view text, std::size_t& pos, bool& pushed_value);
  const OperatorSpec* match_operator(std::string_view text, std::size_t pos) const;
  const FunctionSpec* match_function(std::string_view text, std::size_t pos,
                                     std::size_t& length) const;
  bool push_parameter(double number, std::size_t pos);
  bool push_named(std::string_view name, std::size_t pos);

  const Dialect& dialect_;
  Parameters& parameters_;
  std::size_t max_depth_;
  std::vector<Op> ops_;
  std::vector<Value> values_;
  std::vector<MachineRead> machine_reads_;
  std::string name_;
  EvalError error_;
};

}  // namespace ncpost::gcode::detail
