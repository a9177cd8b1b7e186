#pragma once
// A machine profile: stylesheets/<id>/profile.json (validated here, field by field, against what
// stylesheets/profile.schema.json says) plus stylesheets/<id>/post.xsl (compiled once by the
// ProfileStore). docs/profiles.md describes every field.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::profile {

enum class Arcs : std::uint8_t { Ijk, R, None };
enum class CannedCycles : std::uint8_t { Native, Expand };
enum class NurbsMode : std::uint8_t { Native, Linearize };

struct Range {
  double min = 0;
  double max = 0;
};

struct Limits {
  std::optional<Range> x, y, z;       // travel, in the controller's length unit, machine axes
  std::optional<double> max_feed;     // controller length units per minute
  std::optional<double> max_spindle;  // rpm
  std::optional<std::array<std::int64_t, 2>> tool_number;  // min, max
  std::size_t max_line_length = 0;                         // 0: none
  diag::Severity severity = diag::Severity::Warning;
};

struct Profile {
  std::string id;
  std::string name;
  std::string controller;  // controller family: "linuxcnc", "fanuc", ...
  // output
  std::string extension = ".nc";
  std::string mime_type = "text/plain";
  std::string line_ending = "\n";  // "\n" or "\r\n"
  // The last line of a program that failed or was cancelled after output started; {message}
  // stands for the first error, sanitised by the comment rules.
  std::string error_marker = "(ERROR: {message} - the program is incomplete)";
  std::int64_t program_number = 1;
  std::int64_t program_number_min = 1;
  std::int64_t program_number_max = 9999;
  // block numbers
  xslt::BlockNumbers block{};
  bool block_wrap = true;
  // formats per quantity
  xslt::NumberFormat length{}, angle{}, feed{}, speed{}, dwell{};
  xslt::Units units = xslt::Units::Millimetre;
  // capabilities
  Arcs arcs = Arcs::Ijk;
  bool helical = true;
  CannedCycles canned_cycles = CannedCycles::Expand;
  NurbsMode nurbs = NurbsMode::Linearize;
  double chord_tolerance = 0.001;  // program length units
  xslt::SetupTransform setup{};
  Limits limits{};
};

// Parses and validates profile.json. On any problem returns nullopt and adds PROFILE-001/002
// diagnostics (one per problem, naming the JSON path).
[[nodiscard]] std::optional<Profile> parse_profile(std::string_view json,
                                                   std::vector<diag::Diagnostic>& diagnostics);

// The extension functions' configuration for one job of this profile.
[[nodiscard]] xslt::JobConfig job_config(const Profile& profile);

// A profile ready to render: validated data and its compiled stylesheet (shared, read-only).
struct LoadedProfile {
  Profile profile;
  std::filesystem::path directory;
  std::shared_ptr<const xslt::CompiledStylesheet> stylesheet;
};

struct ProfileSummary {
  std::string id;
  std::string name;
  std::string controller;
};

// The built-in profile directory (${PROJECT_SOURCE_DIR}/stylesheets, compiled in).
[[nodiscard]] std::filesystem::path builtin_directory();

// Profiles in a directory: every sub-folder with a profile.json (except common/). Loading
// compiles post.xsl once (imports allowed from the profile's folder and <dir>/common/) and
// caches the result; later loads of the same id return the cached profile. Thread-safe.
class ProfileStore {
 public:
  explicit ProfileStore(std::filesystem::path directory = builtin_directory());

  [[nodiscard]] const std::filesystem::path& directory() const noexcept { return directory_; }
  // Sorted by id; folders whose profile.json does not parse are reported and left out.
  [[nodiscard]] std::vector<ProfileSummary> list(
      std::vector<xslt::FileDiagnostic>& diagnostics) const;
  // Null with diagnostics (PROFILE-00x, XSLT-0xx) when the profile is unknown or broken.
  [[nodiscard]] std::shared_ptr<const LoadedProfile> load(
      std::string_view id, std::vector<xslt::FileDiagnostic>& diagnostics);

 private:
  std::filesystem::path directory_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const LoadedProfile>, std::less<>> cache_;
};

// A profile id is a folder name: [a-z0-9][a-z0-9._-]*, at most 64 characters.
[[nodiscard]] bool valid_id(std::string_view id) noexcept;

}  // namespace ncpost::profile
