#pragma once
// Machine profiles as the CLI and the server use them: list, look up, replace and remove, with
// outcomes the edges map to exit codes and HTTP statuses; a server's diagnostics never name
// where it is installed (a client learns "profiles/fanuc-0i/post.xsl", not the path).
// The store itself (versions, atomic writes, compiled-stylesheet cache) is engine/profile.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::pipeline {

// Where the installed read-only data is (built-in profiles, web front end, openapi.yaml).
using profile::data_directory;

struct ProfileList {
  std::vector<profile::ProfileSummary> profiles;  // sorted by id
  std::vector<diag::FileDiagnostic> diagnostics;  // folders whose profile.json does not parse
};

enum class LookupOutcome : std::uint8_t {
  Found,
  Unknown,  // no such profile, or not a valid id
  Broken,   // it exists but does not load (profile.json or its stylesheet has errors)
};

struct ProfileLookup {
  LookupOutcome outcome = LookupOutcome::Unknown;
  std::shared_ptr<const profile::LoadedProfile> profile;  // set when Found
  std::vector<diag::FileDiagnostic> diagnostics;
};

enum class PutOutcome : std::uint8_t {
  Created,        // no profile with this id was visible before
  Replaced,       // a new version of a visible profile (a built-in is shadowed)
  ReadOnlyStore,  // the store is not writable
  BadId,          // the id is not a valid profile id
  Reserved,       // the id names something the store did not write (common/, a file...)
  Rejected,       // profile.json or the stylesheet has errors: nothing changed
  WriteFailed,    // the files could not be written: nothing changed
};

struct ProfilePut {
  PutOutcome outcome = PutOutcome::Rejected;
  std::shared_ptr<const profile::LoadedProfile> profile;  // the new active version
  std::vector<diag::FileDiagnostic> diagnostics;
};

class Profiles {
 public:
  // The built-in profiles, read-only.
  Profiles();
  // The profiles of `directory`, read-only (`ncpost --profiles DIR`).
  [[nodiscard]] static std::unique_ptr<Profiles> read_only(const std::filesystem::path& directory);
  // A writable store in `directory` (created when missing) over the built-ins, which show for
  // every id the store does not have (`ncpostd --profiles DIR`). Throws std::filesystem_error
  // when the directory cannot be made.
  [[nodiscard]] static std::unique_ptr<Profiles> writable_over_builtins(
      const std::filesystem::path& directory);
  Profiles(const Profiles&) = delete;
  Profiles& operator=(const Profiles&) = delete;
  ~Profiles();

  [[nodiscard]] ProfileList list() const;
  // A job keeps the version it got, even if the profile is replaced while it runs.
  [[nodiscard]] ProfileLookup find(std::string_view id);
  [[nodiscard]] ProfilePut put(std::string_view id, std::string_view profile_json,
                               std::string_view stylesheet);
  [[nodiscard]] profile::RemoveOutcome remove(std::string_view id);

  [[nodiscard]] bool writable() const noexcept;
  // The store's directory (the built-ins' when it has no directory of its own).
  [[nodiscard]] const std::filesystem::path& directory() const noexcept;
  // Drops cached profiles whose files changed (SIGHUP, or a poll that saw changes).
  void reload();
  [[nodiscard]] bool changed_since_last_scan() const;
  [[nodiscard]] profile::CacheStats cache_stats() const noexcept;

  // From now on, diagnostics name the store's and the built-ins' files relative to
  // "profiles" instead of by their absolute paths (a server's clients learn nothing of where it
  // is installed; a command line user wants the real paths, which is the default).
  void hide_server_paths() noexcept;
  // `diagnostics` as above (unchanged unless hide_server_paths() was called).
  [[nodiscard]] std::vector<diag::FileDiagnostic> without_server_paths(
      std::vector<diag::FileDiagnostic> diagnostics) const;

 private:
  explicit Profiles(std::unique_ptr<profile::ProfileStore> store);
  std::unique_ptr<profile::ProfileStore> store_;
  bool hide_paths_ = false;
};

}  // namespace ncpost::pipeline
