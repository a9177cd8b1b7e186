#pragma once
// Which workingstep each block of a posted program came from: the browser front end links the
// program text to the workingsteps with it (POST /v1/posts with Accept: application/json).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::pipeline {

// Where a workingstep's text begins in the program (or, with id 0, where one ends).
struct WorkingstepMark {
  std::size_t offset = 0;  // in the program text
  std::uint64_t id = 0;
  std::string name;
};

// Where one canonical motion's text lies in the program: [begin, end) offsets, empty when the
// motion wrote nothing (a zero-length move the profile drops, say).
struct MotionMark {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// The 1-based line of `text` that holds each offset (an offset at the end of the text: the
// line after the last). Offsets in any order; O(lines + offsets log lines).
[[nodiscard]] std::vector<std::size_t> lines_at(std::string_view text,
                                                const std::vector<std::size_t>& offsets);

// Per motion, in program order: [first line, last line] of its text, or null when it wrote
// none.
[[nodiscard]] nlohmann::ordered_json motion_lines(std::string_view text,
                                                  const std::vector<MotionMark>& marks);

// From the lines of a posted program and the marks of its workingsteps:
// {"blocks": {block number (or "L" + line) → workingstep id}, "workingsteps": [{id, name,
// first_line, last_line}]}. A block number seen again (the numbering wrapped) is keyed "N#2",
// "N#3", ... Empty when `cancel` was set on the way. Linear in the text.
[[nodiscard]] nlohmann::ordered_json block_map(std::string_view text,
                                               const std::vector<WorkingstepMark>& marks,
                                               const std::atomic<bool>* cancel = nullptr);

}  // namespace ncpost::pipeline
