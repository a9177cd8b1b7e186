#include "ncpost/pipeline/profiles.hpp"

#include <algorithm>

namespace ncpost::pipeline {
namespace {

bool any_code(const std::vector<diag::FileDiagnostic>& diagnostics,
              std::initializer_list<diag::Code> codes) {
  return std::any_of(diagnostics.begin(), diagnostics.end(), [&](const auto& d) {
    return std::find(codes.begin(), codes.end(), d.diagnostic.code) != codes.end();
  });
}

}  // namespace

Profiles::Profiles() : Profiles(std::make_unique<profile::ProfileStore>()) {}

Profiles::Profiles(std::unique_ptr<profile::ProfileStore> store) : store_(std::move(store)) {}

Profiles::~Profiles() = default;

std::unique_ptr<Profiles> Profiles::read_only(const std::filesystem::path& directory) {
  return std::unique_ptr<Profiles>(
      new Profiles(std::make_unique<profile::ProfileStore>(directory)));
}

std::unique_ptr<Profiles> Profiles::writable_over_builtins(const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  profile::StoreOptions options;
  options.writable = true;
  options.fallback = profile::builtin_directory();
  return std::unique_ptr<Profiles>(
      new Profiles(std::make_unique<profile::ProfileStore>(directory, options)));
}

ProfileList Profiles::list() const {
  ProfileList list;
  list.profiles = store_->list(list.diagnostics);
  list.diagnostics = without_server_paths(std::move(list.diagnostics));
  return list;
}

ProfileLookup Profiles::find(std::string_view id) {
  ProfileLookup lookup;
  lookup.profile = store_->load(id, lookup.diagnostics);
  lookup.diagnostics = without_server_paths(std::move(lookup.diagnostics));
  if (lookup.profile)
    lookup.outcome = LookupOutcome::Found;
  else if (any_code(lookup.diagnostics, {diag::Code::ProfileUnknown, diag::Code::ProfileBadId}))
    lookup.outcome = LookupOutcome::Unknown;
  else
    lookup.outcome = LookupOutcome::Broken;
  return lookup;
}

ProfilePut Profiles::put(std::string_view id, std::string_view profile_json,
                         std::string_view stylesheet,
                         std::optional<std::string_view> dialect_json) {
  ProfilePut put;
  if (!store_->writable()) {
    put.outcome = PutOutcome::ReadOnlyStore;
    put.diagnostics.push_back(
        {"request", diag::make(diag::Code::ProfileReadOnly, 0, 0,
                               "the built-in profiles are read-only; start ncpostd with "
                               "--profiles DIR")});
    return put;
  }
  profile::PutResult result = store_->put(id, profile_json, stylesheet, dialect_json);
  put.diagnostics = without_server_paths(std::move(result.diagnostics));
  put.profile = std::move(result.profile);
  if (put.profile)
    put.outcome = result.created ? PutOutcome::Created : PutOutcome::Replaced;
  else if (any_code(put.diagnostics, {diag::Code::ProfileWrite}))
    put.outcome = PutOutcome::WriteFailed;
  else if (any_code(put.diagnostics, {diag::Code::ProfileBadId}))
    put.outcome = PutOutcome::BadId;
  else
    put.outcome = PutOutcome::Rejected;
  return put;
}

profile::RemoveOutcome Profiles::remove(std::string_view id) {
  return store_->remove(id);
}

const std::filesystem::path& Profiles::directory() const noexcept {
  return store_->directory();
}

bool Profiles::writable() const noexcept {
  return store_->writable();
}

void Profiles::reload() {
  store_->reload();
}

bool Profiles::changed_since_last_scan() const {
  return store_->changed_since_last_scan();
}

profile::CacheStats Profiles::cache_stats() const noexcept {
  return store_->cache_stats();
}

void Profiles::hide_server_paths() noexcept {
  hide_paths_ = true;
}

std::vector<diag::FileDiagnostic> Profiles::without_server_paths(
    std::vector<diag::FileDiagnostic> diagnostics) const {
  if (!hide_paths_) return diagnostics;
  // Absolute roots only: a relative --profiles DIR reveals nothing, and a short relative name
  // would match inside ordinary words.
  std::error_code ec;
  const std::string roots[] = {std::filesystem::absolute(store_->directory(), ec).string(),
                               profile::builtin_directory().string()};
  for (auto& d : diagnostics)
    for (const std::string& root : roots) {
      if (root.size() < 2 || root.front() != '/') continue;
      for (std::string* text : {&d.file, &d.diagnostic.message})
        for (auto at = text->find(root); at != std::string::npos; at = text->find(root, at))
          text->replace(at, root.size(), "profiles");
    }
  return diagnostics;
}

}  // namespace ncpost::pipeline
