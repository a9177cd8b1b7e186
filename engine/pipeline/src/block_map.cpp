#include "ncpost/pipeline/block_map.hpp"

#include <algorithm>
#include <cctype>
#include <unordered_map>

namespace ncpost::pipeline {

using json = nlohmann::ordered_json;

nlohmann::ordered_json block_map(std::string_view text, const std::vector<WorkingstepMark>& marks,
                                 const std::atomic<bool>* cancel) {
  json blocks = json::object();
  // Each key is made unique here, so it is appended to the object's list of pairs directly:
  // ordered_json's own insertion looks the key up in that list first, which made the map
  // quadratic in the length of the program.
  auto& entries = blocks.get_ref<json::object_t&>();
  std::unordered_map<std::string, std::size_t> occurrences;
  json workingsteps = json::array();
  std::size_t line_start = 0;
  std::size_t line_number = 0;
  std::size_t mark = 0;
  const WorkingstepMark* current = nullptr;
  json* current_ws = nullptr;
  while (line_start < text.size()) {
    ++line_number;
    if (cancel != nullptr && line_number % 4096 == 0 && cancel->load()) return {};
    // The marks at or before this line's start decide whose line it is.
    while (mark < marks.size() && marks[mark].offset <= line_start) {
      current = marks[mark].id != 0 ? &marks[mark] : nullptr;
      if (current != nullptr) {
        workingsteps.push_back({{"id", current->id},
                                {"name", current->name},
                                {"first_line", nullptr},
                                {"last_line", nullptr}});
        current_ws = &workingsteps.back();
      } else {
        current_ws = nullptr;
      }
      ++mark;
    }
    auto eol = text.find('\n', line_start);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(line_start, eol - line_start);
    if (current != nullptr) {
      std::size_t i = 0;
      while (i < line.size() && (line[i] == ' ' || line[i] == '/')) ++i;
      std::string key;
      if (i < line.size() && (line[i] == 'N' || line[i] == 'n')) {
        std::size_t j = i + 1;
        while (j < line.size() && std::isdigit(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i + 1) key = std::string(line.substr(i + 1, j - i - 1));
      }
      if (key.empty()) {
        key = "L" + std::to_string(line_number);
      } else if (const std::size_t seen = ++occurrences[key]; seen > 1) {
        key += "#" + std::to_string(seen);  // the numbering wrapped: N1234, then N1234#2
      }
      entries.emplace_back(std::move(key), current->id);
      if ((*current_ws)["first_line"].is_null()) (*current_ws)["first_line"] = line_number;
      (*current_ws)["last_line"] = line_number;
    }
    line_start = eol + 1;
  }
  json out;
  out["blocks"] = std::move(blocks);
  out["workingsteps"] = std::move(workingsteps);
  return out;
}

std::vector<std::size_t> lines_at(std::string_view text, const std::vector<std::size_t>& offsets) {
  std::vector<std::size_t> newlines;  // offsets of the '\n's
  for (std::size_t at = text.find('\n'); at != std::string_view::npos; at = text.find('\n', at + 1))
    newlines.push_back(at);
  std::vector<std::size_t> lines;
  lines.reserve(offsets.size());
  for (const std::size_t offset : offsets) {
    // Line k (1-based) holds the offsets after the (k-1)-th newline up to the k-th.
    const auto before = std::lower_bound(newlines.begin(), newlines.end(), offset);
    lines.push_back(static_cast<std::size_t>(before - newlines.begin()) + 1);
  }
  return lines;
}

nlohmann::ordered_json motion_lines(std::string_view text, const std::vector<MotionMark>& marks) {
  std::vector<std::size_t> offsets;
  offsets.reserve(2 * marks.size());
  for (const MotionMark& m : marks) {
    offsets.push_back(m.begin);
    offsets.push_back(m.end > m.begin ? m.end - 1 : m.begin);
  }
  const std::vector<std::size_t> lines = lines_at(text, offsets);
  json out = json::array();
  for (std::size_t k = 0; k < marks.size(); ++k) {
    if (marks[k].end > marks[k].begin)
      out.push_back(json::array({lines[2 * k], lines[2 * k + 1]}));
    else
      out.push_back(nullptr);
  }
  return out;
}

}  // namespace ncpost::pipeline
