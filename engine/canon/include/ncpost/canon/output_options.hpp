#pragma once
// Output options of one workingstep: how the renderer is to write it, as the shop's
// operation-name rules select them (profile.json checks.operation_rules[].options; docs/cls.md,
// "Pre-post checks"). They travel on the workingstep's Begin marker (canon::Begin::options), so
// the trace, the XML form (attributes of <workingstep>) and every profile's stylesheet see them.
//
// In:  option names and values as a profile states them ("block_numbers": "off").
// Out: an OutputOptions value; unset options leave the profile's own behaviour.
//
// The known options (one table: kOutputOptions; docs/profiles.md, "Output options"):
// - block_numbers on|off: the workingstep's blocks carry N numbers or not, whatever the
//   profile's block_numbers.numbered says (ext:block-line(), ext:motion-run(),
//   ext:block-numbering() follow the enclosing <workingstep>);
// - subprogram on|off: the workingstep is written as a subprogram that the main program calls
//   (a profile that has the form lists it in capabilities.output_options).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace ncpost::canon {

enum class Switch : std::uint8_t { Unset, On, Off };

enum class OutputOption : std::uint8_t { BlockNumbers, Subprogram };

struct OutputOptions {
  Switch block_numbers = Switch::Unset;
  Switch subprogram = Switch::Unset;

  [[nodiscard]] Switch get(OutputOption o) const noexcept {
    return o == OutputOption::BlockNumbers ? block_numbers : subprogram;
  }
  void set(OutputOption o, Switch s) noexcept {
    (o == OutputOption::BlockNumbers ? block_numbers : subprogram) = s;
  }
  [[nodiscard]] bool empty() const noexcept {
    return block_numbers == Switch::Unset && subprogram == Switch::Unset;
  }
  friend bool operator==(const OutputOptions&, const OutputOptions&) = default;
};

struct OutputOptionName {
  OutputOption option;
  std::string_view name;  // as in profile.json, the trace and the XML attribute
};
inline constexpr std::array<OutputOptionName, 2> kOutputOptions{{
    {OutputOption::BlockNumbers, "block_numbers"},
    {OutputOption::Subprogram, "subprogram"},
}};

[[nodiscard]] constexpr std::string_view option_name(OutputOption o) noexcept {
  for (const auto& entry : kOutputOptions)
    if (entry.option == o) return entry.name;
  return {};
}

[[nodiscard]] constexpr std::string_view switch_name(Switch s) noexcept {
  return s == Switch::On ? "on" : s == Switch::Off ? "off" : "";
}

// The option called `name`, or false when there is none.
[[nodiscard]] constexpr bool find_output_option(std::string_view name, OutputOption& out) noexcept {
  for (const auto& entry : kOutputOptions) {
    if (entry.name == name) {
      out = entry.option;
      return true;
    }
  }
  return false;
}

// Sets option `name` to `value` ("on" or "off"). Returns an empty string when it did, else what
// is wrong (for a diagnostic that names the option and the value).
[[nodiscard]] inline std::string set_output_option(OutputOptions& options, std::string_view name,
                                                   std::string_view value) {
  OutputOption option{};
  if (!find_output_option(name, option)) {
    std::string known;
    for (const auto& entry : kOutputOptions) {
      if (!known.empty()) known += ", ";
      known += entry.name;
    }
    return "unknown output option '" + std::string(name) + "' (known: " + known + ")";
  }
  if (value == "on") {
    options.set(option, Switch::On);
  } else if (value == "off") {
    options.set(option, Switch::Off);
  } else {
    return "output option '" + std::string(name) + "' must be 'on' or 'off', not '" +
           std::string(value) + "'";
  }
  return {};
}

// Adds the options of `later` that `into` does not set yet: the first rule that sets an option
// decides it, as the first rule with a head decides the head.
inline void add_unset(OutputOptions& into, const OutputOptions& later) noexcept {
  for (const auto& entry : kOutputOptions)
    if (into.get(entry.option) == Switch::Unset) into.set(entry.option, later.get(entry.option));
}

}  // namespace ncpost::canon
