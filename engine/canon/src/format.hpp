#pragma once
// Small formatting helpers shared by the trace and the XML writer (internal to the stage).

#include <charconv>
#include <cstdint>
#include <string>

namespace ncpost::canon::detail {

template <class Integer>
void append_integer(std::string& out, Integer value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer,
             static_cast<std::size_t>(result.ptr - buffer));  // not (first, last): replace()
}

}  // namespace ncpost::canon::detail
