#pragma once
// Which neutral form an upload is, from its first bytes (the "detect" stage of the pipeline).

#include <cstdint>
#include <string_view>

namespace ncpost::pipeline {

enum class InputFormat : std::uint8_t {
  Unknown,
  P21,  // ISO 10303-21: "ISO-10303-21;" after optional comments and whitespace
  P28,  // XML: "<" after an optional byte-order mark and whitespace
  Cl,     // APT/CLSF cutter-location records (cls::looks_like_cl)
  Gcode,  // a controller's program (gcode::looks_like_gcode), read with a profile's dialect
};

[[nodiscard]] InputFormat detect_format(std::string_view bytes) noexcept;
[[nodiscard]] std::string_view to_string(InputFormat format) noexcept;

}  // namespace ncpost::pipeline
