#pragma once
// Parse each schema once per process. The interpreter, the P28 writer and every HTTP worker need
// the same few schemas; SchemaCache hands them one shared, immutable ParseResult.
//
// Thread safety: every member function may be called from any thread. A schema that several
// threads ask for at the same time is parsed once; the others wait for that parse.
// Files are keyed by canonical path, size and modification time, so an edited schema is parsed
// again; texts are keyed by their content. The cache holds at most `max_entries` results and
// drops the least recently used one beyond that, so uploads cannot grow it without bound.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "ncpost/express/parse.hpp"

namespace ncpost::express {

struct SchemaCacheLimits {
  std::size_t max_entries = 16;
  ParseLimits parse;
};

class SchemaCache {
 public:
  explicit SchemaCache(SchemaCacheLimits limits = {});

  // The parse of the file at `path`. Never null. A file that cannot be read gives a result
  // with an IO-001 diagnostic and no schemas; such results are not cached.
  [[nodiscard]] std::shared_ptr<const ParseResult> load_file(const std::filesystem::path& path);
  // The parse of `text`.
  [[nodiscard]] std::shared_ptr<const ParseResult> load_text(std::string_view text);

  // How many results are held, and how many parses this cache has run (for tests and metrics).
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] std::size_t parse_count() const;
  void clear();

  // One cache for the whole process, with default limits.
  [[nodiscard]] static SchemaCache& process_wide();

 private:
  using Result = std::shared_ptr<const ParseResult>;
  struct Entry {
    bool is_file = false;
    std::string key;  // canonical path, or the text itself
    std::uintmax_t size = 0;
    std::filesystem::file_time_type modified{};
    std::shared_future<Result> result;
  };

  // Returns the cached result for `probe`, waiting if another thread is parsing it, or runs
  // `parse` (outside the lock) and caches its result.
  Result get_or_compute(Entry probe, const std::function<Result()>& parse);

  SchemaCacheLimits limits_;
  mutable std::mutex mutex_;
  std::list<Entry> entries_;  // most recently used first; short, so a linear search is fine
  std::size_t parses_ = 0;
};

}  // namespace ncpost::express
