#pragma once
// The checks of one read (checks.hpp configures them): the reader tells it about operations,
// tool names, tool records and tool axes as it meets them; it reports each failed check through
// `report` and collects the options the operation-name rules select.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/cls/checks.hpp"
#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::cls::detail {

class CheckRun {
 public:
  using Report = std::function<void(diag::Diagnostic)>;
  CheckRun(const CheckConfig& config, Report report);

  // A new operation (TOOL PATH/ or an APT tool load) at `line`; `name` may be empty.
  // Returns the output options its operation-name rules select (the first rule setting an
  // option decides it), for the workingstep's Begin marker.
  [[nodiscard]] canon::OutputOptions operation(std::string_view name, std::uint32_t line);
  // The tool the operation names (TOOL PATH/...,TOOL,name).
  void tool_name(std::string_view name, std::uint32_t line, std::uint32_t column);
  // A TLDATA/ or CUTTER/ record (`word`) with what it says about the tool.
  void tool_data(const ToolDimensions& data, std::string_view word, std::uint32_t line);
  // The tool axis in force for a motion at `line` (a unit vector, or not: it is normalised).
  void tool_axis(const canon::Direction& axis, std::uint32_t line, std::uint32_t column);
  // The operation ends (END-OF-PATH, the next operation, the end of the program).
  void end_operation();

  [[nodiscard]] const std::vector<std::pair<std::string, std::string>>& selected_options()
      const noexcept {
    return selected_;
  }

 private:
  void select(const std::pair<std::string, std::string>& option);

  const CheckConfig& config_;
  Report report_;
  std::vector<std::pair<std::string, std::string>> selected_;
  // The operation being read.
  std::string operation_;
  std::uint32_t operation_line_ = 0;
  const HeadType* head_ = nullptr;
  bool axis_reported_ = false;
  std::string tool_name_;
  std::uint32_t tool_name_line_ = 0;
  std::uint32_t tool_name_column_ = 0;
  std::optional<ToolDimensions> from_name_;
  bool tool_data_seen_ = false;
};

}  // namespace ncpost::cls::detail
