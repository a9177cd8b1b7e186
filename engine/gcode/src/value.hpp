#pragma once
// A value as the evaluator sees it: a number that may be FANUC's <vacant> (an unset variable,
// which is not 0) and that remembers whether it came from something only the machine knows
// (a probe result, a PLC bit), so that motion depending on it can be refused.

#include <cstdint>

namespace ncpost::gcode::detail {

struct Value {
  double number = 0;
  bool vacant = false;   // FANUC <vacant>: #0, or a variable never set
  bool machine = false;  // derived from a value only the machine knows

  [[nodiscard]] static Value of(double v) noexcept { return Value{v, false, false}; }
  [[nodiscard]] static Value empty() noexcept { return Value{0, true, false}; }
};

}  // namespace ncpost::gcode::detail
