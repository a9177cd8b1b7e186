#include "ncpost/express/schema_cache.hpp"

#include <fstream>
#include <system_error>

namespace ncpost::express {
namespace {

std::shared_ptr<const ParseResult> io_error(const std::filesystem::path& path,
                                            const std::string& reason) {
  auto result = std::make_shared<ParseResult>();
  result->diagnostics.push_back(
      diag::make(diag::Code::IoCannotRead, 0, 0, "cannot read '" + path.string() + "': " + reason));
  return result;
}

}  // namespace

SchemaCache::SchemaCache(SchemaCacheLimits limits) : limits_(limits) {}

SchemaCache& SchemaCache::process_wide() {
  static SchemaCache cache;
  return cache;
}

std::size_t SchemaCache::size() const {
  const std::lock_guard lock(mutex_);
  return entries_.size();
}

std::size_t SchemaCache::parse_count() const {
  const std::lock_guard lock(mutex_);
  return parses_;
}

void SchemaCache::clear() {
  const std::lock_guard lock(mutex_);
  entries_.clear();
}

SchemaCache::Result SchemaCache::get_or_compute(Entry probe, const std::function<Result()>& parse) {
  std::unique_lock lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if (it->is_file != probe.is_file || it->key != probe.key) continue;
    if (it->size == probe.size && it->modified == probe.modified) {
      entries_.splice(entries_.begin(), entries_, it);  // most recently used first
      std::shared_future<Result> cached = it->result;
      lock.unlock();  // another thread may still be parsing it: wait without the lock
      return cached.get();
    }
    entries_.erase(it);  // the file changed since it was cached
    break;
  }
  std::promise<Result> promise;
  probe.result = promise.get_future().share();
  const bool is_file = probe.is_file;
  const std::string key = probe.key;
  entries_.push_front(std::move(probe));
  while (entries_.size() > limits_.max_entries) entries_.pop_back();
  ++parses_;
  lock.unlock();

  try {
    Result result = parse();
    promise.set_value(result);
    return result;
  } catch (...) {
    // Out of memory, typically: waiters get the same exception, and the entry is dropped so
    // that a later call tries again.
    promise.set_exception(std::current_exception());
    const std::lock_guard relock(mutex_);
    entries_.remove_if([&](const Entry& e) { return e.is_file == is_file && e.key == key; });
    throw;
  }
}

std::shared_ptr<const ParseResult> SchemaCache::load_file(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(path, error);
  if (error) return io_error(path, error.message());
  Entry probe;
  probe.is_file = true;
  probe.key = canonical.string();
  probe.size = std::filesystem::file_size(canonical, error);
  if (!error) probe.modified = std::filesystem::last_write_time(canonical, error);
  if (error) return io_error(path, error.message());

  bool unreadable = false;
  auto result = get_or_compute(probe, [&]() -> Result {
    std::ifstream in(canonical, std::ios::binary);
    std::string text(static_cast<std::size_t>(probe.size), '\0');
    if (!in || !in.read(text.data(), static_cast<std::streamsize>(text.size()))) {
      unreadable = true;
      return io_error(path, "read failed");
    }
    return std::make_shared<const ParseResult>(parse_express(text, limits_.parse));
  });
  if (unreadable) {
    // Do not keep a transient IO failure: drop the entry so the next call tries again.
    const std::lock_guard lock(mutex_);
    entries_.remove_if([&](const Entry& e) { return e.is_file && e.key == probe.key; });
  }
  return result;
}

std::shared_ptr<const ParseResult> SchemaCache::load_text(std::string_view text) {
  Entry probe;
  probe.key = std::string(text);
  probe.size = text.size();
  return get_or_compute(std::move(probe), [&]() -> Result {
    return std::make_shared<const ParseResult>(parse_express(text, limits_.parse));
  });
}

}  // namespace ncpost::express
