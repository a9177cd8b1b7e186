#pragma once
// A machine profile: stylesheets/<id>/profile.json (validated here, field by field, against what
// stylesheets/profile.schema.json says) plus stylesheets/<id>/post.xsl (compiled once by the
// ProfileStore). docs/profiles.md describes every field.

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/output_options.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::profile {

enum class Arcs : std::uint8_t { Ijk, R, None };
enum class CannedCycles : std::uint8_t { Native, Expand };
enum class NurbsMode : std::uint8_t { Native, Linearize };
// Canonical: the stylesheet renders chunks of the canonical program (docs/render.md). Raw: it
// consumes the whole model as one late-bound P28 document, in one transform (render/raw.hpp).
enum class Mode : std::uint8_t { Canonical, Raw };

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

// ---- kinematics: a five-axis machine's rotary axes (docs/kinematics.md) ----
// The renderer turns each motion's tool axis into positions of these two axes
// (render/kinematics.hpp). Roles: head-head: `primary` is the outer head axis (it carries
// `secondary`, the one next to the spindle); table-table: `primary` is the outer table axis (it
// carries `secondary`, the one that carries the workpiece); head-table: `primary` is the head
// axis, `secondary` the table axis.
enum class KinematicsType : std::uint8_t { HeadHead, TableTable, HeadTable };
enum class MachineAxis : std::uint8_t { X, Y, Z };
// Which of the (usually two) solutions for a tool axis is taken when both are within the limits.
enum class RotarySolution : std::uint8_t {
  Shortest,      // the smaller rotary motion from the previous position (ties: positive tilt)
  PositiveTilt,  // the tilting axis at or above 0
  NegativeTilt,  // the tilting axis at or below 0
};

struct RotaryAxis {
  char name = 'C';                    // 'A', 'B' or 'C': its address, and its canonical slot
  MachineAxis axis = MachineAxis::Z;  // the machine axis it turns about
  // +1: a positive angle turns the axis's own part (the head, or the table with the
  // workpiece) by the right-hand rule about the machine axis; -1: the other way.
  int direction = 1;
  bool continuous = false;  // turns without end (no min/max): the shortest way is taken
  double min = 0, max = 0;  // degrees, when not continuous
  // A point of the axis with every rotary axis at 0, in the controller's length unit: for a
  // head axis from the spindle's gauge point, for a table axis from the program zero. Used
  // only without tool-centre-point output.
  std::array<double, 3> pivot{0, 0, 0};
};

struct Kinematics {
  KinematicsType type = KinematicsType::HeadHead;
  RotaryAxis primary{}, secondary{};
  RotarySolution solution = RotarySolution::Shortest;
  // The control keeps the tool tip on the programmed point (TRAORI, G43.4, M128): the post
  // writes the tip and the angles. Otherwise the post moves the linear axes for the pivots.
  bool tool_centre_point = false;
  // A tool axis closer than this (the sine of the angle) to the rotary axis's own direction is
  // on the pole: the rotary angle is then undefined and the previous one is kept.
  double pole_tolerance = 1e-9;
  // KIN-005: a warning when one feed motion turns a rotary axis by more than this many
  // degrees (a solution change at the pole or at a limit); 0: never.
  double rotation_warning = 90;
};

struct Profile {
  std::string id;
  std::string name;
  std::string controller;  // controller family: "linuxcnc", "fanuc", ...
  Mode mode = Mode::Canonical;
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
  // capabilities.output_options: the output options (canon/output_options.hpp) the stylesheet
  // honours. A workingstep that asks for another is written without it, with RENDER-011.
  std::vector<canon::OutputOption> output_options;
  [[nodiscard]] bool honours(canon::OutputOption o) const noexcept {
    for (const auto h : output_options)
      if (h == o) return true;
    return false;
  }
  xslt::SetupTransform setup{};
  Limits limits{};
  // render.motion_runs: the motions the renderer hands to ext:motion-run() as runs instead of
  // one element each (docs/render.md, "Motion runs"). Arcs only with a plane.
  struct MotionRuns {
    bool traverse = false;
    bool feed = false;
    bool arc = false;
    [[nodiscard]] bool any() const noexcept { return traverse || feed || arc; }
  } motion_runs{};
  // The `checks` section as JSON text, for cls::parse_checks (the pre-post checks of CL input;
  // validated there, docs/cls.md). Empty when the profile has none.
  std::optional<std::string> checks_json;
  // A five-axis machine: tool axes become rotary positions (docs/kinematics.md).
  std::optional<Kinematics> kinematics{};
};

// Parses and validates profile.json. On any problem returns nullopt and adds PROFILE-001/002
// diagnostics (one per problem, naming the JSON path).
[[nodiscard]] std::optional<Profile> parse_profile(std::string_view json,
                                                   std::vector<diag::Diagnostic>& diagnostics);

// The extension functions' configuration for one job of this profile.
[[nodiscard]] xslt::JobConfig job_config(const Profile& profile);

// A profile ready to render: validated data and its compiled stylesheet (shared, read-only).
// A job keeps its shared_ptr for its whole run, so a profile replaced meanwhile does not change
// under it.
struct LoadedProfile {
  Profile profile;
  // The folder the files were read from: for an uploaded profile the version's own folder
  // (DIR/.<id>.<hash>), which is removed when a later version replaces it.
  std::filesystem::path directory;
  std::shared_ptr<const xslt::CompiledStylesheet> stylesheet;
  // SHA-256 (hex) of profile.json, post.xsl and every stylesheet it imports, in import order:
  // changes whenever the output of the profile can change (part of the server's ETag).
  std::string version;
  std::string json;  // profile.json as stored (what GET /v1/profiles/{id} returns)
  // dialect.json as stored, when the profile folder has one: how to read this controller's
  // G-code (engine/gcode load_dialect; stylesheets/dialect.schema.json).
  std::optional<std::string> dialect_json;
  bool read_only = false;  // a built-in profile of a store's fallback, or of a read-only store
};

struct ProfileSummary {
  std::string id;
  std::string name;
  std::string controller;
  bool read_only =
      false;  // from the read-only layer (the built-ins): PUT overrides, DELETE refuses
};

// The read-only data ncpost is installed with (docs/deploy.md): built-in profiles, schemas,
// the web front end and openapi.yaml. $NCPOST_DATA_DIR when set, else ../share/ncpost beside
// the running executable's folder (GNUInstallDirs). A build tree has the same layout:
// build/share/ncpost links to the source tree's folders (CMakeLists.txt).
[[nodiscard]] std::filesystem::path data_directory();

// The built-in profile directory: data_directory()/stylesheets.
[[nodiscard]] std::filesystem::path builtin_directory();

struct StoreOptions {
  // put() and remove() are allowed (ncpostd --profiles DIR). Otherwise they refuse
  // (PutResult diagnostics PROFILE-006, RemoveOutcome::ReadOnly).
  bool writable = false;
  // A read-only directory behind the main one (ncpostd: the built-ins), for ids the main one
  // does not have. Its profiles import from its own common/.
  std::optional<std::filesystem::path> fallback;
};

struct PutResult {
  std::shared_ptr<const LoadedProfile> profile;   // the new active version; null when rejected
  std::vector<diag::FileDiagnostic> diagnostics;  // why it was rejected; warnings otherwise
  bool created = false;  // no profile with this id was visible before (HTTP 201, else 200)
};

enum class RemoveOutcome : std::uint8_t {
  Removed,   // gone from the writable directory (a built-in of the same id shows again)
  NotFound,  // no such id (or not a valid id)
  ReadOnly,  // a built-in only, or the store is not writable
  Foreign,   // a folder the store did not write holding more than a profile: left alone
};

struct CacheStats {
  std::uint64_t hits = 0;    // load() answered from the compiled-stylesheet cache
  std::uint64_t misses = 0;  // load() had to read and compile
};

// Profiles in a directory: every sub-folder with a profile.json (except common/ and hidden
// names). Loading compiles post.xsl once (imports allowed from the profile's folder and
// <dir>/common/) and caches the result; later loads of the same id return the cached profile
// until reload() finds its files changed. Thread-safe.
//
// A writable store keeps each uploaded version in its own folder DIR/.<id>.<hash>/ and makes
// DIR/<id> a symbolic link to it, swapped with one rename(2): both files change together, and
// a crash at any moment leaves the old or the new version (docs/profile-admin.md).
class ProfileStore {
 public:
  explicit ProfileStore(std::filesystem::path directory = builtin_directory(),
                        StoreOptions options = {});

  [[nodiscard]] const std::filesystem::path& directory() const noexcept { return directory_; }
  [[nodiscard]] bool writable() const noexcept { return options_.writable; }
  // Sorted by id, both layers (the main directory shadows the fallback); folders whose
  // profile.json does not parse are reported and left out.
  [[nodiscard]] std::vector<ProfileSummary> list(
      std::vector<diag::FileDiagnostic>& diagnostics) const;
  // Null with diagnostics (PROFILE-00x, XSLT-0xx) when the profile is unknown or broken.
  [[nodiscard]] std::shared_ptr<const LoadedProfile> load(
      std::string_view id, std::vector<diag::FileDiagnostic>& diagnostics);

  // Validates and activates a new version of profile `id`: the id, profile.json against the
  // schema (its "id" must equal `id`), then post.xsl must compile with the same security as a
  // built-in (imports only from its own folder and common/), and the dialect, when given, must
  // load (engine/gcode) with the same id. On any failure nothing changes and the previous
  // version stays active. Diagnostics name the files "profile.json", "post.xsl" and
  // "dialect.json" (never the server's paths). Writers are serialised. A version is the files
  // given: one put without a dialect stores a profile without one.
  [[nodiscard]] PutResult put(std::string_view id, std::string_view profile_json,
                              std::string_view stylesheet,
                              std::optional<std::string_view> dialect_json = std::nullopt);
  [[nodiscard]] RemoveOutcome remove(std::string_view id);

  // Drops every cached profile whose files changed on disk (or disappeared); the next load()
  // reads them again. Cheap (stat only): call it on SIGHUP or from a timer.
  void reload();
  // Whether reload() would drop anything, or a profile folder was added or removed, since the
  // last reload() (or construction). Stat only; for a polling loop.
  [[nodiscard]] bool changed_since_last_scan() const;

  [[nodiscard]] CacheStats cache_stats() const noexcept;

 private:
  struct Entry;
  struct Layer {
    std::filesystem::path directory;
    bool read_only = true;
  };
  [[nodiscard]] std::optional<Layer> find_layer(std::string_view id) const;
  [[nodiscard]] std::string scan_signature() const;

  std::filesystem::path directory_;
  StoreOptions options_;
  mutable std::mutex mutex_;  // cache_ and signature_
  std::map<std::string, std::shared_ptr<const Entry>, std::less<>> cache_;
  std::string signature_;   // of the folder listings at the last reload()
  std::mutex write_mutex_;  // one put()/remove() at a time
  std::atomic<std::uint64_t> hits_{0};
  std::atomic<std::uint64_t> misses_{0};
};

// A profile id is a folder name: [a-z0-9][a-z0-9._-]*, at most 64 characters.
[[nodiscard]] bool valid_id(std::string_view id) noexcept;

}  // namespace ncpost::profile
