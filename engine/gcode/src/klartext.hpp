#pragma once
// The state a Heidenhain Klartext program carries between blocks (klartext.cpp); complete here
// so the interpreter, which owns it, can be destroyed where it is defined.

#include <array>
#include <map>

#include "interpreter.hpp"

namespace ncpost::gcode::detail {

struct Interpreter::KlartextState {
  double cc_x = 0, cc_y = 0;  // the circle centre (CC), program units
  bool cc = false;
  int cycle = 0;                  // the cycle CYCL DEF defined last (200, 203), 0: none
  std::map<int, double> q;        // its Q parameters
  std::array<double, 3> datum{};  // cycle 7's shift
  int datum_line = 0;             // 7.1 .. 7.3 follow 7.0
  bool dwell_next = false;        // CYCL DEF 9.0 read: 9.1 gives the time
};

}  // namespace ncpost::gcode::detail
