#include <algorithm>
#include <fstream>
#include <sstream>

#include "ncpost/profile/profile.hpp"

#ifndef NCPOST_BUILTIN_PROFILES
#define NCPOST_BUILTIN_PROFILES "stylesheets"
#endif

namespace ncpost::profile {
namespace {

namespace fs = std::filesystem;

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void add(std::vector<xslt::FileDiagnostic>& out, const fs::path& file, diag::Code code,
         std::string message) {
  out.push_back({file.string(), diag::make(code, 0, 0, std::move(message))});
}

std::optional<Profile> read_profile_json(const fs::path& file,
                                         std::vector<xslt::FileDiagnostic>& out) {
  auto text = read_text(file);
  if (!text) {
    add(out, file, diag::Code::ProfileDirectory, "cannot read " + file.string());
    return std::nullopt;
  }
  std::vector<diag::Diagnostic> diagnostics;
  auto profile = parse_profile(*text, diagnostics);
  for (auto& d : diagnostics) out.push_back({file.string(), std::move(d)});
  return profile;
}

}  // namespace

fs::path builtin_directory() {
  return NCPOST_BUILTIN_PROFILES;
}

ProfileStore::ProfileStore(fs::path directory) : directory_(std::move(directory)) {}

std::vector<ProfileSummary> ProfileStore::list(
    std::vector<xslt::FileDiagnostic>& diagnostics) const {
  std::vector<ProfileSummary> out;
  std::error_code ec;
  fs::directory_iterator it(directory_, ec);
  if (ec) {
    add(diagnostics, directory_, diag::Code::ProfileDirectory,
        "cannot read the profile directory: " + ec.message());
    return out;
  }
  for (const auto& entry : it) {
    const auto id = entry.path().filename().string();
    if (!entry.is_directory() || id == "common" || !valid_id(id)) continue;
    const auto file = entry.path() / "profile.json";
    if (!fs::exists(file)) continue;
    if (auto p = read_profile_json(file, diagnostics))
      out.push_back({p->id, p->name, p->controller});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

std::shared_ptr<const LoadedProfile> ProfileStore::load(
    std::string_view id, std::vector<xslt::FileDiagnostic>& diagnostics) {
  {
    std::lock_guard lock(mutex_);
    if (auto it = cache_.find(id); it != cache_.end()) return it->second;
  }
  const fs::path folder = directory_ / std::string(id);
  if (!valid_id(id) || !fs::is_regular_file(folder / "profile.json")) {
    add(diagnostics, directory_, diag::Code::ProfileUnknown,
        "no profile '" + std::string(id) + "' in " + directory_.string());
    return nullptr;
  }
  auto profile = read_profile_json(folder / "profile.json", diagnostics);
  if (!profile) return nullptr;
  if (profile->id != id) {
    add(diagnostics, folder / "profile.json", diag::Code::ProfileInvalid,
        "/id: '" + profile->id + "' differs from the folder name '" + std::string(id) + "'");
    return nullptr;
  }
  const std::array<fs::path, 2> roots{folder, directory_ / "common"};
  auto compiled = xslt::compile(folder / "post.xsl", roots);
  for (auto& d : compiled.diagnostics) diagnostics.push_back(std::move(d));
  if (!compiled.ok()) {
    add(diagnostics, folder / "post.xsl", diag::Code::ProfileStylesheet,
        "the stylesheet of profile '" + std::string(id) + "' does not compile");
    return nullptr;
  }
  auto loaded = std::make_shared<LoadedProfile>(
      LoadedProfile{std::move(*profile), folder, compiled.stylesheet});
  std::lock_guard lock(mutex_);
  return cache_.try_emplace(std::string(id), std::move(loaded)).first->second;
}

}  // namespace ncpost::profile
