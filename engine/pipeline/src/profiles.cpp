#include "ncpost/pipeline/profiles.hpp"

#include <algorithm>
#include <cctype>

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
                         std::string_view stylesheet) {
  ProfilePut put;
  if (!store_->writable()) {
    put.outcome = PutOutcome::ReadOnlyStore;
    put.diagnostics.push_back(
        {"request", diag::make(diag::Code::ProfileReadOnly, 0, 0,
                               "the built-in profiles are read-only; start ncpostd with "
                               "--profiles DIR")});
    return put;
  }
  profile::PutResult result = store_->put(id, profile_json, stylesheet);
  put.diagnostics = without_server_paths(std::move(result.diagnostics));
  put.profile = std::move(result.profile);
  if (put.profile)
    put.outcome = result.created ? PutOutcome::Created : PutOutcome::Replaced;
  else if (any_code(put.diagnostics, {diag::Code::ProfileWrite}))
    put.outcome = PutOutcome::WriteFailed;
  else if (any_code(put.diagnostics, {diag::Code::ProfileBadId}))
    put.outcome = PutOutcome::BadId;
  else if (any_code(put.diagnostics, {diag::Code::ProfileReserved}))
    put.outcome = PutOutcome::Reserved;
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

namespace {

// Whether text[at] may begin a path: the text's start, or after a quote, a space or '='.
bool path_may_start(const std::string& text, std::size_t at) {
  return at == 0 || std::string_view(" '\"=(").find(text[at - 1]) != std::string_view::npos;
}

// Every whole path component sequence "<root>" in text (followed by '/', a quote, a space,
// ':' or the end) becomes "profiles".
void replace_root(std::string& text, const std::string& root) {
  static constexpr std::string_view kAs = "profiles";
  for (auto at = text.find(root); at != std::string::npos; at = text.find(root, at)) {
    const std::size_t end = at + root.size();
    const bool whole = path_may_start(text, at) &&
                       (end == text.size() ||
                        std::string_view("/ '\":),").find(text[end]) != std::string_view::npos);
    if (!whole) {
      ++at;
      continue;
    }
    text.replace(at, root.size(), kAs);
    at += kAs.size();
  }
}

// "profiles/.<id>@<hex>[-<hex>]/" (a store version folder) becomes "profiles/<id>/": the
// version is the store's business, the id is what the client named.
void hide_version_folders(std::string& text) {
  static constexpr std::string_view kPrefix = "profiles/.";
  for (auto at = text.find(kPrefix); at != std::string::npos; at = text.find(kPrefix, at + 1)) {
    const std::size_t id_start = at + kPrefix.size();
    const std::size_t sign = text.find('@', id_start);
    const std::size_t slash = text.find('/', id_start);
    if (sign == std::string::npos || slash == std::string::npos || sign > slash) continue;
    const bool hex_version = std::all_of(
        text.begin() + static_cast<std::ptrdiff_t>(sign + 1),
        text.begin() + static_cast<std::ptrdiff_t>(slash),
        [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) || c == '-'; });
    if (!hex_version || slash == sign + 1) continue;
    text.erase(sign, slash - sign);
    text.erase(id_start - 1, 1);
  }
}

}  // namespace

std::vector<diag::FileDiagnostic> Profiles::without_server_paths(
    std::vector<diag::FileDiagnostic> diagnostics) const {
  if (!hide_paths_) return diagnostics;
  // The store's directory as given, absolute and with its links resolved, and the built-ins:
  // whichever form a message carries.
  std::error_code ec;
  std::vector<std::string> roots{
      store_->directory().lexically_normal().string(),
      std::filesystem::absolute(store_->directory(), ec).string(),
      std::filesystem::weakly_canonical(store_->directory(), ec).string(),
      profile::builtin_directory().string()};
  // Longest first, so that a root inside another is not replaced in part.
  std::sort(roots.begin(), roots.end(),
            [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  for (auto& d : diagnostics)
    for (std::string* text : {&d.file, &d.diagnostic.message}) {
      for (const std::string& root : roots) {
        std::string trimmed = root;
        while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
        if (trimmed.empty() || trimmed == "." || trimmed == "/") continue;
        replace_root(*text, trimmed);
      }
      hide_version_folders(*text);
    }
  return diagnostics;
}

}  // namespace ncpost::pipeline
