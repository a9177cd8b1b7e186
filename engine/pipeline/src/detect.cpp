#include "ncpost/pipeline/detect.hpp"

#include <cctype>

namespace ncpost::pipeline {

InputFormat detect_format(std::string_view bytes) noexcept {
  if (bytes.starts_with("\xEF\xBB\xBF")) bytes.remove_prefix(3);
  // Only the start is looked at; a P21 file may open with comments of any length.
  for (std::size_t guard = 0; guard < 64; ++guard) {
    while (!bytes.empty() && std::isspace(static_cast<unsigned char>(bytes.front())))
      bytes.remove_prefix(1);
    if (bytes.starts_with("/*")) {
      const std::size_t end = bytes.find("*/", 2);
      if (end == std::string_view::npos) return InputFormat::Unknown;
      bytes.remove_prefix(end + 2);
      continue;
    }
    break;
  }
  // A P21 file whose first line is missing still reads as P21, so that the reader can say
  // precisely what is wrong (P21-020) instead of "not a format ncpost reads".
  if (bytes.starts_with("ISO-10303-21") || bytes.starts_with("HEADER;")) return InputFormat::P21;
  if (bytes.starts_with("<")) return InputFormat::P28;
  return InputFormat::Unknown;
}

std::string_view to_string(InputFormat format) noexcept {
  switch (format) {
    case InputFormat::P21:
      return "p21";
    case InputFormat::P28:
      return "p28";
    case InputFormat::Unknown:
      break;
  }
  return "unknown";
}

}  // namespace ncpost::pipeline
