// ProfileStore: list, load (with the compiled-stylesheet cache), put, remove and reload.
// Storage layout and the crash argument: docs/profile-admin.md.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "ncpost/gcode/gcode.hpp"
#include "ncpost/profile/profile.hpp"
#include "sha256.hpp"

// The data folder seen from the folder of the executable (GNUInstallDirs: ../share/ncpost).
#ifndef NCPOST_DATA_FROM_BIN
#define NCPOST_DATA_FROM_BIN "../share/ncpost"
#endif

namespace ncpost::profile {

namespace fs = std::filesystem;

// What reload() compares: a stat of every file a cached profile was built from.
struct Stamp {
  fs::path path;
  bool link = false;  // lstat (the DIR/<id> entry itself) rather than stat
  std::string value;
};

struct ProfileStore::Entry {
  std::shared_ptr<const LoadedProfile> loaded;
  std::vector<Stamp> stamps;
};

namespace {

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return ss.str();
}

void add(std::vector<diag::FileDiagnostic>& out, const fs::path& file, diag::Code code,
         std::string message) {
  out.push_back({file.string(), diag::make(code, 0, 0, std::move(message))});
}

std::optional<Profile> parse_json_text(const std::string& text, const std::string& file_name,
                                       std::vector<diag::FileDiagnostic>& out) {
  std::vector<diag::Diagnostic> diagnostics;
  auto profile = parse_profile(text, diagnostics);
  for (auto& d : diagnostics) out.push_back({file_name, std::move(d)});
  return profile;
}

std::optional<Profile> read_profile_json(const fs::path& file,
                                         std::vector<diag::FileDiagnostic>& out) {
  auto text = read_text(file);
  if (!text) {
    add(out, file, diag::Code::ProfileDirectory, "cannot read " + file.string());
    return std::nullopt;
  }
  return parse_json_text(*text, file.string(), out);
}

std::string stamp_of(const fs::path& path, bool link) {
  struct stat st {};
  const int rc = link ? ::lstat(path.c_str(), &st) : ::stat(path.c_str(), &st);
  if (rc != 0) return "-";
  if (link && S_ISLNK(st.st_mode)) {
    std::error_code ec;
    return "l:" + fs::read_symlink(path, ec).string();
  }
  // Inode and change time catch a file replaced by rename even within one mtime tick.
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + ":" +
         std::to_string(st.st_size) + ":" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec) + ":" + std::to_string(st.st_ctim.tv_sec) + "." +
         std::to_string(st.st_ctim.tv_nsec);
}

Stamp make_stamp(fs::path path, bool link) {
  std::string value = stamp_of(path, link);
  return {std::move(path), link, std::move(value)};
}

// Length-prefixed pieces, so that moving bytes from one file to the next changes the hash.
void hash_piece(detail::Sha256& h, std::string_view bytes) {
  h.update(std::to_string(bytes.size()));
  h.update(":");
  h.update(bytes);
}

std::string random_hex() {
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  static constexpr char kHex[] = "0123456789abcdef";
  std::uint64_t v = rng();
  std::string out(16, '0');
  for (char& c : out) {
    c = kHex[v & 0xf];
    v >>= 4;
  }
  return out;
}

std::string errno_text(int e) {
  return std::strerror(e);
}

// fsync of a directory makes the renames and creations inside it durable.
bool fsync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

// Written completely and synced, or an error message.
std::optional<std::string> write_new_file(const fs::path& path, std::string_view bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return "cannot create " + path.filename().string() + ": " + errno_text(errno);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      return "cannot write " + path.filename().string() + ": " + errno_text(e);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    return "cannot sync " + path.filename().string() + ": " + errno_text(e);
  }
  if (::close(fd) != 0)
    return "cannot close " + path.filename().string() + ": " + errno_text(errno);
  return std::nullopt;
}

bool starts_with_path(const fs::path& path, const fs::path& prefix) {
  auto p = path.begin();
  for (auto r = prefix.begin(); r != prefix.end(); ++r, ++p) {
    if (r->empty()) continue;
    if (p == path.end() || *p != *r) return false;
  }
  return true;
}

// Names the store uses beside the profiles. '@' and '~' cannot occur in an id, so the id of
// every such name is known: ".<id>@<hash>" is a version folder, ".<id>~<random>" a temporary
// folder or link that a crash may have left.
std::string version_prefix(std::string_view id) {
  return "." + std::string(id) + "@";
}
std::string temp_prefix(std::string_view id) {
  return "." + std::string(id) + "~";
}

// Why the store may not write or delete DIR/<id>, or empty when it may. It only replaces what
// it wrote (a link to one of its version folders) or a profile placed by hand (a folder with
// nothing but a profile's files); the shared templates, other files and folders holding
// anything else are the operator's.
std::string foreign_entry(const fs::path& directory, std::string_view id) {
  if (id == "common") return "'common' holds the templates every profile imports";
  const fs::path entry = directory / std::string(id);
  struct stat st {};
  if (::lstat(entry.c_str(), &st) != 0) return {};
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    const std::string target = fs::read_symlink(entry, ec).string();
    if (!ec && target.rfind(version_prefix(id), 0) == 0 && target.find('/') == std::string::npos)
      return {};
    return "'" + std::string(id) + "' is a link the profile store did not make";
  }
  if (!S_ISDIR(st.st_mode)) return "'" + std::string(id) + "' is a file, not a profile";
  std::error_code ec;
  bool has_profile = false;
  for (const auto& file : fs::directory_iterator(entry, ec)) {
    const std::string name = file.path().filename().string();
    const bool profile_file =
        name == "profile.json" || name == "post.xsl" || name == "dialect.json";
    if (!profile_file || !file.is_regular_file(ec))
      return "the folder '" + std::string(id) + "' holds '" + name +
             "', which is not a profile's file";
    has_profile = has_profile || name == "profile.json";
  }
  if (ec) return "the folder '" + std::string(id) + "' cannot be read";
  if (!has_profile) return "the folder '" + std::string(id) + "' holds no profile.json";
  return {};
}

}  // namespace

fs::path data_directory() {
  if (const char* chosen = std::getenv("NCPOST_DATA_DIR"); chosen != nullptr && *chosen != '\0')
    return chosen;
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  // Without /proc the executable's folder is unknown; the current folder is the only guess left.
  const fs::path bin = error ? fs::current_path(error) : executable.parent_path();
  return (bin / NCPOST_DATA_FROM_BIN).lexically_normal();
}

fs::path builtin_directory() {
  // Canonical, because the build tree's data folder links to the source tree's stylesheets and
  // the store names files by their real path: a server hides this prefix from its diagnostics.
  std::error_code error;
  fs::path directory = data_directory() / "stylesheets";
  fs::path real = fs::weakly_canonical(directory, error);
  return error ? directory : real;
}

ProfileStore::ProfileStore(fs::path directory, StoreOptions options)
    : directory_(std::move(directory)), options_(std::move(options)) {
  signature_ = scan_signature();
}

std::optional<ProfileStore::Layer> ProfileStore::find_layer(std::string_view id) const {
  if (!valid_id(id)) return std::nullopt;
  std::error_code ec;
  if (fs::is_regular_file(directory_ / std::string(id) / "profile.json", ec)) {
    return Layer{directory_, !options_.writable};
  }
  if (options_.fallback &&
      fs::is_regular_file(*options_.fallback / std::string(id) / "profile.json", ec)) {
    return Layer{*options_.fallback, true};
  }
  return std::nullopt;
}

std::vector<ProfileSummary> ProfileStore::list(
    std::vector<diag::FileDiagnostic>& diagnostics) const {
  std::vector<ProfileSummary> out;
  std::vector<std::pair<fs::path, bool>> layers{{directory_, !options_.writable}};
  if (options_.fallback) layers.emplace_back(*options_.fallback, true);
  for (const auto& [dir, read_only] : layers) {
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) {
      // A writable directory that does not exist yet is simply empty; the first put() makes it.
      if (!(options_.writable && dir == directory_ && !fs::exists(dir)))
        add(diagnostics, dir, diag::Code::ProfileDirectory,
            "cannot read the profile directory: " + ec.message());
      continue;
    }
    for (const auto& entry : it) {
      const auto id = entry.path().filename().string();
      if (id == "common" || !valid_id(id) || !entry.is_directory(ec)) continue;
      if (std::any_of(out.begin(), out.end(), [&](const auto& s) { return s.id == id; })) continue;
      const auto file = entry.path() / "profile.json";
      if (!fs::exists(file, ec)) continue;
      if (auto p = read_profile_json(file, diagnostics)) {
        ProfileSummary s;
        s.id = p->id;
        s.name = p->name;
        s.controller = p->controller;
        s.read_only = read_only;
        out.push_back(std::move(s));
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

namespace {

struct Built {
  std::shared_ptr<LoadedProfile> loaded;
  std::vector<Stamp> stamps;
};

// Reads and compiles the profile in `folder` (a real folder: the caller resolved the link).
// `json` is given when the caller has the text already (put()).
Built build(const fs::path& folder, std::string_view id, const std::vector<fs::path>& roots,
            std::optional<std::string> json, std::vector<diag::FileDiagnostic>& diagnostics) {
  Built out;
  const fs::path json_file = folder / "profile.json";
  const fs::path xsl_file = folder / "post.xsl";
  const fs::path dialect_file = folder / "dialect.json";
  out.stamps.push_back(make_stamp(json_file, false));
  out.stamps.push_back(make_stamp(xsl_file, false));
  // Stamped present or not, so that adding one is seen by reload().
  out.stamps.push_back(make_stamp(dialect_file, false));
  if (!json) {
    json = read_text(json_file);
    if (!json) {
      add(diagnostics, json_file, diag::Code::ProfileDirectory,
          "cannot read " + json_file.string());
      return out;
    }
  }
  auto profile = parse_json_text(*json, json_file.string(), diagnostics);
  if (!profile) return out;
  if (profile->id != id) {
    add(diagnostics, json_file, diag::Code::ProfileInvalid,
        "/id: '" + profile->id + "' differs from the folder name '" + std::string(id) + "'");
    return out;
  }
  auto compiled = xslt::compile(xsl_file, roots);
  for (auto& d : compiled.diagnostics) diagnostics.push_back(std::move(d));
  if (!compiled.ok()) {
    add(diagnostics, xsl_file, diag::Code::ProfileStylesheet,
        "the stylesheet of profile '" + std::string(id) + "' does not compile");
    return out;
  }
  std::optional<std::string> dialect;
  std::error_code exists_error;
  if (fs::exists(dialect_file, exists_error)) {
    dialect = read_text(dialect_file);
    if (!dialect) {
      add(diagnostics, dialect_file, diag::Code::ProfileDirectory,
          "cannot read " + dialect_file.string());
      return out;
    }
  }
  detail::Sha256 h;
  h.update("ncpost-profile-version-1");
  hash_piece(h, *json);
  // The dialect belongs to the version too (what a translation reads by); without one the
  // version is what it was before dialects existed.
  if (dialect) {
    h.update("dialect");
    hash_piece(h, *dialect);
  }
  for (const fs::path& f : compiled.stylesheet->files()) {
    if (f != compiled.stylesheet->files().front()) out.stamps.push_back(make_stamp(f, false));
    const auto text = read_text(f);
    if (!text) {
      add(diagnostics, f, diag::Code::ProfileDirectory, "cannot read " + f.string());
      return out;
    }
    hash_piece(h, *text);
  }
  auto loaded = std::make_shared<LoadedProfile>();
  loaded->profile = std::move(*profile);
  loaded->directory = folder;
  loaded->stylesheet = std::move(compiled.stylesheet);
  loaded->version = h.hex();
  loaded->json = std::move(*json);
  loaded->dialect_json = std::move(dialect);
  out.loaded = std::move(loaded);
  return out;
}

}  // namespace

std::shared_ptr<const LoadedProfile> ProfileStore::load(
    std::string_view id, std::vector<diag::FileDiagnostic>& diagnostics) {
  {
    std::lock_guard lock(mutex_);
    if (auto it = cache_.find(id); it != cache_.end()) {
      hits_.fetch_add(1, std::memory_order_relaxed);
      return it->second->loaded;
    }
  }
  misses_.fetch_add(1, std::memory_order_relaxed);
  // A put() (of this or another process) may swap the link and remove the old version folder
  // while we read it; then the link points elsewhere and reading again gives the new version.
  for (int attempt = 0;; ++attempt) {
    const auto layer = find_layer(id);
    if (!layer) {
      add(diagnostics, directory_, diag::Code::ProfileUnknown,
          "no profile '" + std::string(id) + "' in " + directory_.string());
      return nullptr;
    }
    const fs::path entry = layer->directory / std::string(id);
    std::vector<Stamp> stamps{make_stamp(directory_ / std::string(id), true)};
    if (layer->directory != directory_) stamps.push_back(make_stamp(entry, true));
    std::error_code ec;
    const fs::path folder = fs::canonical(entry, ec);
    std::vector<diag::FileDiagnostic> attempt_diagnostics;
    Built built;
    if (ec) {
      add(attempt_diagnostics, entry, diag::Code::ProfileDirectory,
          "cannot resolve " + entry.string() + ": " + ec.message());
    } else {
      std::vector<fs::path> roots{folder, layer->directory / "common"};
      if (options_.fallback && layer->directory == directory_)
        roots.push_back(*options_.fallback / "common");
      built = build(folder, id, roots, std::nullopt, attempt_diagnostics);
    }
    if (!built.loaded) {
      // The version folder may also have been removed and written again under the same name
      // (a re-upload of the same content): its files' inodes tell.
      bool moved = fs::canonical(entry, ec) != folder;
      for (const Stamp& s : built.stamps) moved = moved || stamp_of(s.path, s.link) != s.value;
      if (moved && attempt < 3) continue;
      for (auto& d : attempt_diagnostics) diagnostics.push_back(std::move(d));
      return nullptr;
    }
    for (auto& d : attempt_diagnostics) diagnostics.push_back(std::move(d));
    built.loaded->read_only = layer->read_only;
    stamps.insert(stamps.end(), built.stamps.begin(), built.stamps.end());
    auto fresh = std::make_shared<const Entry>(Entry{std::move(built.loaded), std::move(stamps)});
    std::lock_guard lock(mutex_);
    return cache_.try_emplace(std::string(id), std::move(fresh)).first->second->loaded;
  }
}

PutResult ProfileStore::put(std::string_view id, std::string_view profile_json,
                            std::string_view stylesheet,
                            std::optional<std::string_view> dialect_json) {
  PutResult result;
  auto& diagnostics = result.diagnostics;
  if (!valid_id(id)) {
    add(diagnostics, "profile.json", diag::Code::ProfileBadId,
        "'" + std::string(id.substr(0, 80)) +
            "' is not a profile id: [a-z0-9][a-z0-9._-]*, at most 64 characters");
    return result;
  }
  if (!options_.writable) {
    add(diagnostics, "profile.json", diag::Code::ProfileReadOnly,
        "the built-in profiles are read-only; start ncpostd with --profiles DIR");
    return result;
  }
  const std::string json(profile_json);
  {
    std::vector<diag::FileDiagnostic> parsed;
    const auto profile = parse_json_text(json, "profile.json", parsed);
    for (auto& d : parsed) diagnostics.push_back(std::move(d));
    if (!profile) return result;
    if (profile->id != id) {
      add(diagnostics, "profile.json", diag::Code::ProfileInvalid,
          "/id: '" + profile->id + "' differs from the id in the path '" + std::string(id) + "'");
      return result;
    }
  }
  if (dialect_json) {
    auto dialect = gcode::load_dialect(*dialect_json);
    for (auto& d : dialect.diagnostics) diagnostics.push_back({"dialect.json", std::move(d)});
    if (!dialect.dialect) return result;
    if (dialect.dialect->id != id) {
      add(diagnostics, "dialect.json", diag::Code::GcodeDialectInvalid,
          "/id: '" + dialect.dialect->id + "' differs from the id in the path '" + std::string(id) +
              "'");
      return result;
    }
  }

  std::lock_guard write_lock(write_mutex_);
  if (const std::string foreign = foreign_entry(directory_, id); !foreign.empty()) {
    add(diagnostics, "profile.json", diag::Code::ProfileReserved,
        foreign + "; the profile store only replaces profiles");
    return result;
  }
  const auto fail = [&](std::string message) {
    add(diagnostics, "profile.json", diag::Code::ProfileWrite, std::move(message));
    return std::move(result);
  };
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec) return fail("cannot create the profile directory: " + ec.message());
  // Uploads import "../common/...". A profile directory without its own common/ gets a link to
  // the built-in one, so that the built-in templates serve uploads as they serve built-ins.
  const fs::path common = directory_ / "common";
  struct stat st {};
  if (::lstat(common.c_str(), &st) != 0 && options_.fallback) {
    const fs::path builtin_common = fs::absolute(*options_.fallback / "common", ec);
    if (!ec && fs::is_directory(builtin_common, ec)) {
      if (::symlink(builtin_common.c_str(), common.c_str()) == 0) fsync_directory(directory_);
    }
  }

  const bool existed = find_layer(id).has_value();
  detail::Sha256 content;
  hash_piece(content, json);
  hash_piece(content, stylesheet);
  if (dialect_json) {
    content.update("dialect");
    hash_piece(content, *dialect_json);
  }
  std::string name = version_prefix(id) + content.hex().substr(0, 16);
  fs::path version = directory_ / name;
  const fs::path entry = directory_ / std::string(id);
  const fs::path active = fs::canonical(entry, ec);
  bool reused = false;
  if (::lstat(version.c_str(), &st) == 0) {
    // The same content was stored before (a re-upload, or a version a crash left behind):
    // reuse it when it is intact, otherwise write beside it.
    reused =
        S_ISDIR(st.st_mode) && read_text(version / "profile.json") == json &&
        read_text(version / "post.xsl") == std::string(stylesheet) &&
        read_text(version / "dialect.json") ==
            (dialect_json ? std::optional<std::string>(std::string(*dialect_json)) : std::nullopt);
    if (!reused) {
      name += "-" + random_hex().substr(0, 8);
      version = directory_ / name;
    }
  }
  if (!reused) {
    // Both files are complete and synced before the folder gets its final name, so a version
    // folder is never partial; a crash before the rename leaves a temporary the next put()
    // removes.
    const fs::path temp = directory_ / (temp_prefix(id) + random_hex());
    if (!fs::create_directory(temp, ec) || ec)
      return fail("cannot create a folder in the profile directory: " + ec.message());
    std::optional<std::string> error = write_new_file(temp / "profile.json", json);
    if (!error) error = write_new_file(temp / "post.xsl", stylesheet);
    if (!error && dialect_json) error = write_new_file(temp / "dialect.json", *dialect_json);
    if (!error && !fsync_directory(temp)) error = "cannot sync the new version's folder";
    if (!error && ::rename(temp.c_str(), version.c_str()) != 0)
      error = "cannot rename the new version's folder: " + errno_text(errno);
    if (!error && !fsync_directory(directory_)) error = "cannot sync the profile directory";
    if (error) {
      fs::remove_all(temp, ec);
      return fail(*error);
    }
  }

  const fs::path real_version = fs::canonical(version, ec);
  std::vector<fs::path> roots{real_version, common};
  if (options_.fallback) roots.push_back(*options_.fallback / "common");
  std::vector<diag::FileDiagnostic> built_diagnostics;
  Built built = build(real_version, id, roots, json, built_diagnostics);
  // Name the uploaded files as the client knows them, not by the server's paths.
  std::vector<std::pair<fs::path, std::string>> renames{{real_version, ""},
                                                        {fs::canonical(common, ec), "common"}};
  if (options_.fallback)
    renames.emplace_back(fs::canonical(*options_.fallback / "common", ec), "common");
  for (auto& d : built_diagnostics) {
    const fs::path file(d.file);
    for (const auto& [prefix, as] : renames) {
      if (prefix.empty() || !starts_with_path(file, prefix)) continue;
      d.file = (fs::path(as) / file.lexically_relative(prefix)).string();
      break;
    }
    diagnostics.push_back(std::move(d));
  }
  if (!built.loaded) {
    if (real_version != active) fs::remove_all(version, ec);
    return result;
  }

  // The switch: a new symbolic link renamed over DIR/<id> replaces both files in one step.
  // A profile folder placed by hand (a real directory) is exchanged with the link atomically
  // (renameat2 RENAME_EXCHANGE) and then removed.
  const fs::path link = directory_ / (temp_prefix(id) + random_hex());
  if (::symlink(name.c_str(), link.c_str()) != 0)
    return fail("cannot create the profile link: " + errno_text(errno));
  const bool replace_folder = ::lstat(entry.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
  const int rc = replace_folder
                     ? ::renameat2(AT_FDCWD, link.c_str(), AT_FDCWD, entry.c_str(), RENAME_EXCHANGE)
                     : ::rename(link.c_str(), entry.c_str());
  if (rc != 0) {
    const int e = errno;
    fs::remove(link, ec);
    if (real_version != active) fs::remove_all(version, ec);
    return fail("cannot activate the new version: " + errno_text(e));
  }
  if (!fsync_directory(directory_)) {
    // The switch happened (other processes see it); only its durability across a power loss
    // is in doubt. Report it as a warning rather than pretend nothing changed.
    add(diagnostics, "profile.json", diag::Code::ProfileWrite,
        "the profile directory could not be synced; the new version is active");
    diagnostics.back().diagnostic.severity = diag::Severity::Warning;
  }

  // Old versions and crash leftovers of this id. Running jobs hold their compiled stylesheet
  // in memory and never read these files again.
  for (const auto& e : fs::directory_iterator(directory_, ec)) {
    const std::string n = e.path().filename().string();
    const bool ours = n.rfind(version_prefix(id), 0) == 0 || n.rfind(temp_prefix(id), 0) == 0;
    if (ours && n != name) fs::remove_all(e.path(), ec);
  }

  built.loaded->read_only = false;
  std::vector<Stamp> stamps{make_stamp(entry, true)};
  stamps.insert(stamps.end(), built.stamps.begin(), built.stamps.end());
  result.profile = built.loaded;
  result.created = !existed;
  auto fresh = std::make_shared<const Entry>(Entry{std::move(built.loaded), std::move(stamps)});
  std::lock_guard lock(mutex_);
  cache_.insert_or_assign(std::string(id), std::move(fresh));
  return result;
}

RemoveOutcome ProfileStore::remove(std::string_view id) {
  if (!valid_id(id)) return RemoveOutcome::NotFound;
  std::lock_guard write_lock(write_mutex_);
  const auto layer = find_layer(id);
  if (!layer) return RemoveOutcome::NotFound;
  if (layer->read_only) return RemoveOutcome::ReadOnly;
  if (!foreign_entry(directory_, id).empty()) return RemoveOutcome::Foreign;
  const fs::path entry = directory_ / std::string(id);
  struct stat st {};
  if (::lstat(entry.c_str(), &st) != 0) return RemoveOutcome::NotFound;
  std::error_code ec;
  if (S_ISLNK(st.st_mode)) {
    if (::unlink(entry.c_str()) != 0) return RemoveOutcome::ReadOnly;
  } else {
    // A folder placed by hand: renamed away in one step, then deleted at leisure.
    const fs::path temp = directory_ / (temp_prefix(id) + random_hex());
    if (::rename(entry.c_str(), temp.c_str()) != 0) return RemoveOutcome::ReadOnly;
  }
  fsync_directory(directory_);
  for (const auto& e : fs::directory_iterator(directory_, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(version_prefix(id), 0) == 0 || n.rfind(temp_prefix(id), 0) == 0)
      fs::remove_all(e.path(), ec);
  }
  std::lock_guard lock(mutex_);
  cache_.erase(std::string(id));
  return RemoveOutcome::Removed;
}

void ProfileStore::reload() {
  std::lock_guard lock(mutex_);
  for (auto it = cache_.begin(); it != cache_.end();) {
    const bool stale =
        std::any_of(it->second->stamps.begin(), it->second->stamps.end(),
                    [](const Stamp& s) { return stamp_of(s.path, s.link) != s.value; });
    it = stale ? cache_.erase(it) : std::next(it);
  }
  signature_ = scan_signature();
}

bool ProfileStore::changed_since_last_scan() const {
  std::lock_guard lock(mutex_);
  if (scan_signature() != signature_) return true;
  for (const auto& [id, entry] : cache_) {
    for (const Stamp& s : entry->stamps)
      if (stamp_of(s.path, s.link) != s.value) return true;
  }
  return false;
}

std::string ProfileStore::scan_signature() const {
  std::vector<std::string> lines;
  std::vector<fs::path> dirs{directory_};
  if (options_.fallback) dirs.push_back(*options_.fallback);
  for (const fs::path& dir : dirs) {
    std::error_code ec;
    lines.push_back(dir.string() + "=" + stamp_of(dir, false));
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string n = e.path().filename().string();
      if (!valid_id(n)) continue;
      lines.push_back(e.path().string() + "=" + stamp_of(e.path(), true));
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

CacheStats ProfileStore::cache_stats() const noexcept {
  return {hits_.load(std::memory_order_relaxed), misses_.load(std::memory_order_relaxed)};
}

}  // namespace ncpost::profile
