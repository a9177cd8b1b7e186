#include "evaluator.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "lexer.hpp"

namespace ncpost::gcode::detail {

namespace {

constexpr int kUnaryPrecedence = 100;
// LinuxCNC compares for equality within this tolerance (interp_internal.hh TOLERANCE_EQUAL).
constexpr double kEqualTolerance = 1e-4;
constexpr double kDegree = std::numbers::pi / 180.0;

bool is_ident_char(char c) noexcept {
  return is_letter(c) || is_digit(c) || c == '_';
}

Value combine(double number, const Value& a, const Value& b) {
  return Value{number, false, a.machine || b.machine};
}

}  // namespace

Evaluator::Evaluator(const Dialect& dialect, Parameters& parameters, std::size_t max_depth)
    : dialect_(dialect), parameters_(parameters), max_depth_(max_depth) {}

namespace {

// Numbers of more than 15 digits (rare): correctly rounded by from_chars.
[[gnu::noinline, gnu::cold]] bool long_number(const char* first, const char* last,
                                              double& out) noexcept {
  if (*first == '.') {
    // from_chars wants a digit first; ".5" is read as "0.5" (correctly rounded), and one too
    // long for the buffer as its digits over a power of ten.
    char buffer[128];
    const auto length = static_cast<std::size_t>(last - first);
    if (length < sizeof buffer) {
      buffer[0] = '0';
      std::memcpy(buffer + 1, first, length);
      const auto r = std::from_chars(buffer, buffer + length + 1, out, std::chars_format::fixed);
      return r.ec == std::errc{};
    }
    double frac = 0;
    const auto r = std::from_chars(first + 1, last, frac);
    (void)r;
    double scale = 1;
    for (const char* p = first + 1; p < last; ++p) scale *= 10;
    out = frac / scale;
    return true;
  }
  const auto r = std::from_chars(first, last, out, std::chars_format::fixed);
  return r.ec == std::errc{};
}

}  // namespace

bool Evaluator::scan_number(std::string_view text, std::size_t& pos, double& out,
                            bool& integer) noexcept {
  // Exact powers of ten (every one up to 1e22 is a double).
  static constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const char* const first = text.data() + pos;
  const char* const end = text.data() + text.size();
  const char* p = first;
  // The digits as an integer; it may wrap past 19 digits, but then the number is read another
  // way.
  std::uint64_t mantissa = 0;
  const auto digit_run = [&] {
    for (; p < end && static_cast<unsigned char>(*p - '0') < 10; ++p)
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
  };
  digit_run();
  const auto integer_digits = static_cast<std::size_t>(p - first);
  std::size_t fraction_digits = 0;
  integer = true;
  if (p < end && *p == '.') {
    integer = false;
    const char* const point = p++;
    digit_run();
    fraction_digits = static_cast<std::size_t>(p - point - 1);
  }
  const std::size_t digits = integer_digits + fraction_digits;
  if (digits == 0) return false;
  if (digits <= 15) {
    // Up to 15 digits the mantissa and the power of ten are exact doubles, and one division of
    // exact operands is correctly rounded: the same value from_chars gives, without its cost.
    out = static_cast<double>(mantissa) / kPow10[fraction_digits];
  } else if (!long_number(first, p, out)) {
    return false;
  }
  pos += static_cast<std::size_t>(p - first);
  return true;
}

bool Evaluator::fail(std::size_t pos, diag::Code code, std::string message) {
  error_.pos = pos;
  error_.code = code;
  error_.message = std::move(message);
  return false;
}

const OperatorSpec* Evaluator::match_operator(std::string_view text, std::size_t pos) const {
  if (pos >= text.size()) return nullptr;
  for (const auto& spec : dialect_.expressions.operators) {
    const auto& s = spec.spelling;
    // The first character settles most candidates without a string compare (a hot path).
    if (s.front() != text[pos] || text.compare(pos, s.size(), s) != 0) continue;
    if (is_letter(s.front()) && !dialect_.ignore_whitespace) {
      const std::size_t after = pos + s.size();
      if (after < text.size() && is_ident_char(text[after])) continue;
      if (pos > 0 && is_ident_char(text[pos - 1])) continue;
    }
    return &spec;
  }
  return nullptr;
}

const FunctionSpec* Evaluator::match_function(std::string_view text, std::size_t pos,
                                              std::size_t& length) const {
  const FunctionSpec* best = nullptr;
  length = 0;
  if (pos >= text.size()) return nullptr;
  for (const auto& spec : dialect_.expressions.functions) {
    const auto& s = spec.name;
    if (s.size() <= length || s.front() != text[pos] || text.compare(pos, s.size(), s) != 0)
      continue;
    if (!dialect_.ignore_whitespace) {
      const std::size_t after = pos + s.size();
      if (after < text.size() && is_ident_char(text[after])) continue;
    }
    best = &spec;
    length = s.size();
  }
  return best;
}

bool Evaluator::push_parameter(double number, std::size_t pos) {
  const ParamRead r = parameters_.get(number);
  switch (r.status) {
    case ParamStatus::Ok:
      break;
    case ParamStatus::NotInteger:
      return fail(pos, diag::Code::GcodeBadParameter, "parameter number is not an integer");
    case ParamStatus::OutOfRange:
      return fail(pos, diag::Code::GcodeBadParameter, "parameter number out of range");
    case ParamStatus::ReadOnly:
    case ParamStatus::Undefined:
      return fail(pos, diag::Code::GcodeBadParameter, "parameter cannot be read");
  }
  if (r.machine) {
    char buf[32];
    const auto n = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(std::round(number)));
    const char prefix = dialect_.parameters.style == ParameterStyle::R   ? 'R'
                        : dialect_.parameters.style == ParameterStyle::Q ? 'Q'
                                                                         : '#';
    machine_reads_.push_back(
        {std::string(1, prefix) + std::string(buf, n.ptr) + " (" + r.machine->name + ")",
         r.machine->assumed});
  }
  values_.push_back(r.value);
  return true;
}

bool Evaluator::push_named(std::string_view name, std::size_t pos) {
  for (const auto& prefix : dialect_.parameters.machine_name_prefixes) {
    if (name.size() >= prefix.size() && name.compare(0, prefix.size(), prefix) == 0) {
      machine_reads_.push_back({std::string(name), 0});
      values_.push_back(Value{0, false, true});
      return true;
    }
  }
  const auto v = parameters_.get_named(name);
  if (!v)
    return fail(pos, diag::Code::GcodeBadParameter,
                "named parameter #<" + std::string(name) + "> read before it was set");
  values_.push_back(*v);
  return true;
}

// #<name>: LinuxCNC lower-cases names (spaces were squeezed out already); we read upper case
// text, so names are compared in upper case.
bool Evaluator::read_parameter_name(std::string_view text, std::size_t& pos, std::string& name) {
  const std::size_t start = pos;  // at '<'
  const std::size_t close = text.find('>', pos + 1);
  if (close == std::string_view::npos)
    return fail(start, diag::Code::GcodeBadParameter, "named parameter not terminated by '>'");
  name.assign(text.substr(pos + 1, close - pos - 1));
  if (name.empty()) return fail(start, diag::Code::GcodeBadParameter, "empty parameter name");
  pos = close + 1;
  return true;
}

bool Evaluator::read_operand(std::string_view text, std::size_t& pos, bool& pushed_value) {
  pushed_value = false;
  const char c = text[pos];
  const auto& ex = dialect_.expressions;
  const ParameterStyle style = dialect_.parameters.style;
  if (is_digit(c) || c == '.') {
    double v = 0;
    bool integer = false;
    const std::size_t start = pos;
    if (!scan_number(text, pos, v, integer))
      return fail(start, diag::Code::GcodeBadNumber, "malformed number");
    values_.push_back(Value::of(v));
    pushed_value = true;
    return true;
  }
  if (c == '-' || c == '+') {
    ops_.push_back({OpKind::Unary, Operator::Add, c == '-' ? UnaryOp::Neg : UnaryOp::Pos,
                    Function::Sin, kUnaryPrecedence, 1, false, pos});
    ++pos;
    return true;
  }
  if (c == ex.open) {
    ops_.push_back({OpKind::Open, Operator::Add, UnaryOp::Neg, Function::Sin, 0, 1, false, pos});
    ++pos;
    return true;
  }
  if (c == '#' && style == ParameterStyle::Hash) {
    if (pos + 1 < text.size() && text[pos + 1] == '<' && dialect_.parameters.named) {
      const std::size_t start = pos;
      ++pos;
      if (!read_parameter_name(text, pos, name_)) return false;
      if (!push_named(name_, start)) return false;
      pushed_value = true;
      return true;
    }
    ops_.push_back({OpKind::Unary, Operator::Add, UnaryOp::Hash, Function::Sin, kUnaryPrecedence, 1,
                    false, pos});
    ++pos;
    return true;
  }
  if (c == '$') {
    // A system variable ($AA_IM[Z], $P_TOOLNO): only the machine knows it.
    std::size_t end = pos + 1;
    while (end < text.size() && is_ident_char(text[end])) ++end;
    if (end < text.size() && text[end] == '[') {
      const std::size_t close = text.find(']', end);
      end = close == std::string_view::npos ? text.size() : close + 1;
    }
    machine_reads_.push_back({std::string(text.substr(pos, end - pos)), 0});
    values_.push_back(Value{0, false, true});
    pos = end;
    pushed_value = true;
    return true;
  }
  if (is_letter(c)) {
    std::size_t length = 0;
    if (const FunctionSpec* f = match_function(text, pos, length)) {
      const std::size_t start = pos;
      pos += length;
      std::size_t p = pos;
      while (p < text.size() && text[p] == ' ') ++p;
      if (f->function == Function::Exists) {
        // EXISTS[#<name>]: whether the named parameter is set (the name is not evaluated);
        // EXISTS[#n]: whether n is a parameter number.
        if (p >= text.size() || text[p] != ex.open || p + 2 >= text.size() || text[p + 1] != '#')
          return fail(p, diag::Code::GcodeBadExpression, "expected # reading parameter in EXISTS");
        std::size_t q = p + 2;
        bool exists = false;
        if (text[q] == '<') {
          if (!read_parameter_name(text, q, name_)) return false;
          exists = parameters_.exists_named(name_);
        } else {
          // The number may itself be an expression (##2): evaluated with fresh stacks.
          Evaluator inner(dialect_, parameters_, max_depth_ > 0 ? max_depth_ - 1 : 0);
          Value n;
          if (max_depth_ == 0 || !inner.evaluate(text, q, Mode::Primary, n)) {
            error_ = inner.error();
            return false;
          }
          exists = n.number >= 0 && n.number < static_cast<double>(dialect_.parameters.count) &&
                   std::abs(n.number - std::round(n.number)) < 1e-4;
        }
        if (q >= text.size() || text[q] != ex.close)
          return fail(q, diag::Code::GcodeBadExpression, "expected ] reading bracketed parameter");
        values_.push_back(Value::of(exists ? 1 : 0));
        pos = q + 1;
        pushed_value = true;
        return true;
      }
      if (p < text.size() && text[p] == ex.open) {
        ops_.push_back({OpKind::Call, Operator::Add, UnaryOp::Fn, f->function, 0, 1, false, start});
        ops_.push_back({OpKind::Open, Operator::Add, UnaryOp::Neg, f->function, 0, 1, true, p});
        pos = p + 1;
        return true;
      }
      if (style == ParameterStyle::Hash)
        return fail(p, diag::Code::GcodeBadExpression,
                    "expected " + std::string(1, ex.open) + " after " + f->name);
      // Klartext style: SIN Q1 applies to the next value.
      ops_.push_back({OpKind::Unary, Operator::Add, UnaryOp::Fn, f->function, kUnaryPrecedence, 1,
                      false, start});
      return true;
    }
    if (style == ParameterStyle::R || style == ParameterStyle::Q) {
      // Rn / Qn (QLn, QRn: Heidenhain's local and remanent Q), or a user variable name.
      std::size_t end = pos;
      while (end < text.size() && is_ident_char(text[end])) ++end;
      const std::string_view ident = text.substr(pos, end - pos);
      const char letter = style == ParameterStyle::R ? 'R' : 'Q';
      std::size_t digits_at = 1;
      if (style == ParameterStyle::Q && ident.size() > 2 && (ident[1] == 'L' || ident[1] == 'R'))
        digits_at = 2;
      bool numbered = ident.size() > digits_at && ident[0] == letter;
      for (std::size_t k = digits_at; numbered && k < ident.size(); ++k)
        numbered = is_digit(ident[k]);
      if (numbered) {
        double number = 0;
        std::from_chars(ident.data() + digits_at, ident.data() + ident.size(), number);
        // QL and QR live beside Q in one table, offset by 10000 and 20000.
        if (digits_at == 2) number += ident[1] == 'L' ? 10000 : 20000;
        const std::size_t start = pos;
        pos = end;
        if (!push_parameter(number, start)) return false;
        pushed_value = true;
        return true;
      }
      if (ident == "PI") {
        values_.push_back(Value::of(std::numbers::pi));
        pos = end;
        pushed_value = true;
        return true;
      }
      if (ident == "TRUE" || ident == "FALSE") {
        values_.push_back(Value::of(ident == "TRUE" ? 1 : 0));
        pos = end;
        pushed_value = true;
        return true;
      }
      if (ident == "NOT") {
        ops_.push_back({OpKind::Unary, Operator::Add, UnaryOp::Not, Function::Sin, kUnaryPrecedence,
                        1, false, pos});
        pos = end;
        return true;
      }
      if (!ident.empty()) {
        const std::size_t start = pos;
        pos = end;
        if (!push_named(ident, start)) return false;
        pushed_value = true;
        return true;
      }
    }
  }
  return fail(pos, diag::Code::GcodeBadExpression,
              c == ex.close ? "expected a value before " + std::string(1, c)
                            : "expected a value, found '" + std::string(1, c) + "'");
}

bool Evaluator::function(Function fn, const Value* a, std::size_t count, Value& out) {
  const auto need = [&](std::size_t n) {
    return count == n ? true : fail(0, diag::Code::GcodeBadExpression, "wrong argument count");
  };
  const bool two =
      fn == Function::Atan2 || fn == Function::Min || fn == Function::Max || fn == Function::Pow;
  if (!need(two ? 2 : 1)) return false;
  const double x = a[0].number;
  const bool machine = a[0].machine || (two && a[1].machine);
  double r = 0;
  switch (fn) {
    case Function::Sin:
      r = std::sin(x * kDegree);
      break;
    case Function::Cos:
      r = std::cos(x * kDegree);
      break;
    case Function::Tan:
      r = std::tan(x * kDegree);
      break;
    case Function::Asin:
      if (x < -1 || x > 1) return fail(0, diag::Code::GcodeMathError, "ASIN of a value beyond 1");
      r = std::asin(x) / kDegree;
      break;
    case Function::Acos:
      if (x < -1 || x > 1) return fail(0, diag::Code::GcodeMathError, "ACOS of a value beyond 1");
      r = std::acos(x) / kDegree;
      break;
    case Function::Atan:
      r = std::atan(x) / kDegree;
      break;
    case Function::Atan2:
      r = std::atan2(x, a[1].number) / kDegree;
      break;
    case Function::Sqrt:
      if (x < 0) return fail(0, diag::Code::GcodeMathError, "square root of a negative number");
      r = std::sqrt(x);
      break;
    case Function::Abs:
      r = std::abs(x);
      break;
    case Function::Round:
      r = std::round(x);
      break;
    case Function::Fix:
      r = std::floor(x);
      break;
    case Function::Fup:
      r = std::ceil(x);
      break;
    case Function::Trunc:
      r = std::trunc(x);
      break;
    case Function::Ln:
      if (x <= 0) return fail(0, diag::Code::GcodeMathError, "logarithm of a number <= 0");
      r = std::log(x);
      break;
    case Function::Log10:
      if (x <= 0) return fail(0, diag::Code::GcodeMathError, "logarithm of a number <= 0");
      r = std::log10(x);
      break;
    case Function::Exp:
      r = std::exp(x);
      break;
    case Function::Square:
      r = x * x;
      break;
    case Function::Not:
      r = x == 0 ? 1 : 0;
      break;
    case Function::Min:
      r = std::min(x, a[1].number);
      break;
    case Function::Max:
      r = std::max(x, a[1].number);
      break;
    case Function::Sign:
      r = x > 0 ? 1 : (x < 0 ? -1 : 0);
      break;
    case Function::Frac:
      r = x - std::trunc(x);
      break;
    case Function::Neg:
      r = -x;
      break;
    case Function::Bin:
    case Function::Bcd: {
      // FANUC BIN/BCD convert between binary and binary-coded decimal (PLC signals).
      auto v = static_cast<std::int64_t>(std::llround(x));
      std::int64_t result = 0;
      std::int64_t scale = 1;
      if (fn == Function::Bin) {
        for (; v > 0; v >>= 4, scale *= 10) result += (v & 0xf) * scale;
      } else {
        for (; v > 0; v /= 10, scale <<= 4) result += (v % 10) * scale;
      }
      r = static_cast<double>(result);
      break;
    }
    case Function::Away:
      r = x < 0 ? std::floor(x) : std::ceil(x);
      break;
    case Function::Pow:
      r = std::pow(x, a[1].number);
      break;
    case Function::Exists:
      return fail(0, diag::Code::GcodeBadExpression, "EXISTS takes #<name>");
  }
  if (!std::isfinite(r)) return fail(0, diag::Code::GcodeMathError, "result is not finite");
  out = Value{r, false, machine};
  return true;
}

bool Evaluator::binary(Operator op, const Value& a, const Value& b, Value& out) {
  const double x = a.number;
  const double y = b.number;
  double r = 0;
  switch (op) {
    case Operator::Add:
      r = x + y;
      break;
    case Operator::Sub:
      r = x - y;
      break;
    case Operator::Mul:
      r = x * y;
      break;
    case Operator::Div:
      if (y == 0) return fail(0, diag::Code::GcodeMathError, "division by zero");
      r = x / y;
      break;
    case Operator::IntDiv:
      if (y == 0) return fail(0, diag::Code::GcodeMathError, "division by zero");
      r = std::trunc(x / y);
      break;
    case Operator::Mod:
      if (y == 0) return fail(0, diag::Code::GcodeMathError, "MOD by zero");
      // LinuxCNC's MOD is never negative for a positive divisor: -7 MOD 3 = 2.
      r = std::fmod(x, y);
      if (r < 0) r += std::abs(y);
      break;
    case Operator::Pow:
      r = std::pow(x, y);
      if (!std::isfinite(r)) return fail(0, diag::Code::GcodeMathError, "power without a result");
      break;
    case Operator::Eq:
    case Operator::Ne: {
      // FANUC: <vacant> equals only <vacant>.
      bool equal =
          (a.vacant || b.vacant) ? (a.vacant == b.vacant) : std::abs(x - y) < kEqualTolerance;
      r = (op == Operator::Eq) == equal ? 1 : 0;
      break;
    }
    case Operator::Gt:
      r = x > y ? 1 : 0;
      break;
    case Operator::Ge:
      r = x >= y ? 1 : 0;
      break;
    case Operator::Lt:
      r = x < y ? 1 : 0;
      break;
    case Operator::Le:
      r = x <= y ? 1 : 0;
      break;
    case Operator::And:
      r = (x != 0 && y != 0) ? 1 : 0;
      break;
    case Operator::Or:
      r = (x != 0 || y != 0) ? 1 : 0;
      break;
    case Operator::Xor:
      r = ((x != 0) != (y != 0)) ? 1 : 0;
      break;
    case Operator::BitAnd:
    case Operator::BitOr:
    case Operator::BitXor: {
      const auto i = std::llround(x);
      const auto j = std::llround(y);
      r = static_cast<double>(op == Operator::BitAnd  ? (i & j)
                              : op == Operator::BitOr ? (i | j)
                                                      : (i ^ j));
      break;
    }
  }
  out = combine(r, a, b);
  return true;
}

bool Evaluator::apply_unary(const Op& op) {
  if (values_.empty()) return fail(op.pos, diag::Code::GcodeBadExpression, "missing value");
  Value v = values_.back();
  values_.pop_back();
  switch (op.unary) {
    case UnaryOp::Neg:
      values_.push_back(Value{-v.number, false, v.machine});
      return true;
    case UnaryOp::Pos:
      values_.push_back(Value{v.number, false, v.machine});
      return true;
    case UnaryOp::Not:
      values_.push_back(Value{v.number == 0 ? 1.0 : 0.0, false, v.machine});
      return true;
    case UnaryOp::Hash: {
      if (v.vacant) return fail(op.pos, diag::Code::GcodeBadParameter, "#<vacant> as a number");
      if (!push_parameter(v.number, op.pos)) return false;
      values_.back().machine = values_.back().machine || v.machine;
      return true;
    }
    case UnaryOp::Fn: {
      Value r;
      if (!function(op.fn, &v, 1, r)) {
        error_.pos = op.pos;
        return false;
      }
      values_.push_back(r);
      return true;
    }
  }
  return true;
}

bool Evaluator::reduce_one() {
  const Op op = ops_.back();
  ops_.pop_back();
  if (op.kind == OpKind::Unary) return apply_unary(op);
  if (op.kind != OpKind::Binary || values_.size() < 2)
    return fail(op.pos, diag::Code::GcodeBadExpression, "malformed expression");
  const Value b = values_.back();
  values_.pop_back();
  const Value a = values_.back();
  values_.pop_back();
  Value r;
  if (!binary(op.binary, a, b, r)) {
    error_.pos = op.pos;
    return false;
  }
  values_.push_back(r);
  return true;
}

bool Evaluator::reduce_while(int precedence) {
  while (!ops_.empty() &&
         (ops_.back().kind == OpKind::Unary || ops_.back().kind == OpKind::Binary) &&
         ops_.back().precedence >= precedence) {
    if (!reduce_one()) return false;
  }
  return true;
}

bool Evaluator::evaluate(std::string_view text, std::size_t& pos, Mode mode, Value& out) {
  ops_.clear();
  values_.clear();
  const auto& ex = dialect_.expressions;
  std::size_t depth = 0;
  bool expect_operand = true;
  const std::size_t max_ops = 4 * max_depth_ + 16;
  const std::size_t start = pos;
  while (true) {
    if (expect_operand) {
      while (pos < text.size() && text[pos] == ' ') ++pos;
      if (pos >= text.size())
        return fail(pos, diag::Code::GcodeBadExpression,
                    pos == start ? "expected a value" : "expression ends where a value belongs");
      bool pushed = false;
      const std::size_t before = ops_.size();
      if (!read_operand(text, pos, pushed)) return false;
      if (ops_.size() > max_ops)
        return fail(pos, diag::Code::GcodeBadExpression,
                    "expression nested deeper than ReadOptions::max_expression_depth");
      if (ops_.size() > before && ops_.back().kind == OpKind::Open) {
        if (++depth > max_depth_)
          return fail(pos, diag::Code::GcodeBadExpression,
                      "brackets nested deeper than ReadOptions::max_expression_depth");
      }
      if (pushed) {
        expect_operand = false;
        if (depth == 0 && mode == Mode::Primary) break;
      }
      continue;
    }
    // Expecting an operator, a close bracket, a comma or the end.
    std::size_t p = pos;
    while (p < text.size() && text[p] == ' ') ++p;
    if (p > pos && depth == 0 && mode == Mode::FullToSpace) break;
    if (p >= text.size()) {
      pos = p;
      break;
    }
    const char c = text[p];
    if (c == ex.close && depth > 0) {
      while (!ops_.empty() && ops_.back().kind != OpKind::Open)
        if (!reduce_one()) return false;
      if (ops_.empty()) return fail(p, diag::Code::GcodeBadExpression, "unbalanced brackets");
      const Op open = ops_.back();
      ops_.pop_back();
      --depth;
      pos = p + 1;
      if (open.call_bracket) {
        if (ops_.empty() || ops_.back().kind != OpKind::Call)
          return fail(p, diag::Code::GcodeBadExpression, "malformed function call");
        const Op call = ops_.back();
        ops_.pop_back();
        const auto count = static_cast<std::size_t>(open.args);
        if (values_.size() < count)
          return fail(call.pos, diag::Code::GcodeBadExpression, "missing function argument");
        // LinuxCNC and FANUC: ATAN[y]/[x] is the two-argument arc tangent.
        if (call.fn == Function::Atan && count == 1 && ex.atan_slash && pos + 1 < text.size() &&
            text[pos] == '/' && text[pos + 1] == ex.open) {
          ops_.push_back(
              {OpKind::Call, Operator::Add, UnaryOp::Fn, Function::Atan2, 0, 1, false, call.pos});
          ops_.push_back(
              {OpKind::Open, Operator::Add, UnaryOp::Neg, Function::Atan2, 0, 2, true, pos + 1});
          ++depth;
          pos += 2;
          expect_operand = true;
          continue;
        }
        Value r;
        if (!function(call.fn, values_.data() + values_.size() - count, count, r)) {
          error_.pos = call.pos;
          return false;
        }
        values_.resize(values_.size() - count);
        values_.push_back(r);
      } else if (open.args != 1) {
        return fail(open.pos, diag::Code::GcodeBadExpression, "a list where one value belongs");
      }
      if (depth == 0 && mode == Mode::Primary) break;
      continue;
    }
    if (c == ',' && depth > 0) {
      while (!ops_.empty() && ops_.back().kind != OpKind::Open)
        if (!reduce_one()) return false;
      if (ops_.empty() || !ops_.back().call_bracket)
        return fail(p, diag::Code::GcodeBadExpression, "',' outside a function's arguments");
      ++ops_.back().args;
      pos = p + 1;
      expect_operand = true;
      continue;
    }
    const OperatorSpec* o = match_operator(text, p);
    if (!o) {
      if (depth == 0) {
        pos = p;
        break;
      }
      return fail(p, diag::Code::GcodeBadExpression,
                  "expected an operator or " + std::string(1, ex.close) + ", found '" +
                      std::string(1, c) + "'");
    }
    if (!reduce_while(o->precedence)) return false;
    ops_.push_back(
        {OpKind::Binary, o->op, UnaryOp::Neg, Function::Sin, o->precedence, 1, false, p});
    pos = p + o->spelling.size();
    expect_operand = true;
  }
  if (depth > 0) {
    for (auto it = ops_.rbegin(); it != ops_.rend(); ++it)
      if (it->kind == OpKind::Open)
        return fail(it->pos, diag::Code::GcodeBadExpression,
                    std::string(1, ex.open) + " without its " + std::string(1, ex.close));
  }
  while (!ops_.empty())
    if (!reduce_one()) return false;
  if (values_.size() != 1)
    return fail(start, diag::Code::GcodeBadExpression, "malformed expression");
  out = values_.back();
  return true;
}

}  // namespace ncpost::gcode::detail
