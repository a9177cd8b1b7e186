#include "ncpost/p21/model.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "ncpost/p21/strings.hpp"

namespace ncpost::p21 {
namespace {

constexpr std::uint32_t kNoInstance = 0xFFFFFFFFu;

char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

// The arenas of a large file are reserved at their upper bound and filled front to back: with
// 2 MB pages that is one page fault where there were 512 (a fifth of a 100 MB read was the
// kernel clearing 4 kB pages). Only whole 2 MB pages inside the reservation are advised; the
// kernel's transparent huge pages in "madvise" mode (Debian's default) act on it, and where it
// cannot, nothing changes.
void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHugePage - 1) & ~(kHugePage - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHugePage - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace

std::size_t Model::CaseInsensitiveHash::operator()(std::string_view s) const noexcept {
  std::size_t h = 1469598103934665603ull;  // FNV-1a over upper-cased bytes
  for (char c : s) {
    h ^= static_cast<unsigned char>(upper(c));
    h *= 1099511628211ull;
  }
  return h;
}

bool Model::CaseInsensitiveEqual::operator()(std::string_view a,
                                             std::string_view b) const noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}

Model::Model() : text_(std::make_unique<std::string>()) {}
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;
Model::~Model() = default;

const Instance* Model::header_entity(std::string_view name) const {
  const CaseInsensitiveEqual eq;
  for (const auto& h : header_)
    if (eq(keyword(h.keyword), name)) return &h;
  return nullptr;
}

const Instance* Model::find(std::uint64_t id) const {
  if (!dense_index_.empty() || sparse_index_.empty()) {
    if (id >= dense_index_.size()) return nullptr;
    const std::uint32_t index = dense_index_[id];
    return index == kNoInstance ? nullptr : &instances_[index];
  }
  auto it =
      std::lower_bound(sparse_index_.begin(), sparse_index_.end(), id,
                       [](const auto& entry, std::uint64_t key) { return entry.first < key; });
  if (it == sparse_index_.end() || it->first != id) return nullptr;
  return &instances_[it->second];
}

std::optional<KeywordId> Model::keyword_id(std::string_view name) const {
  auto it = keyword_index_.find(name);
  if (it == keyword_index_.end()) return std::nullopt;
  return it->second;
}

bool Model::has_type(const Instance& instance, std::string_view name) const {
  const CaseInsensitiveEqual eq;
  if (!is_complex(instance)) return eq(type_name(instance), name);
  for (Value record : params(instance))
    if (record.kind() == ValueKind::Typed && eq(keyword(record.keyword_id()), name)) return true;
  return false;
}

std::span<const std::uint32_t> Model::instance_indices_of(KeywordId k) const {
  if (k + 1 >= by_keyword_start_.size()) return {};
  return {by_keyword_.data() + by_keyword_start_[k],
          by_keyword_start_[k + 1] - by_keyword_start_[k]};
}

std::vector<const Instance*> Model::instances_of(std::string_view name) const {
  std::vector<const Instance*> out;
  if (auto k = keyword_id(name))
    for (std::uint32_t index : instance_indices_of(*k)) out.push_back(&instances_[index]);
  return out;
}

std::optional<std::span<const Value>> Model::record_params(const Instance& instance,
                                                           std::string_view name) const {
  const CaseInsensitiveEqual eq;
  if (!is_complex(instance)) {
    if (eq(type_name(instance), name)) return params(instance);
    return std::nullopt;
  }
  for (Value record : params(instance)) {
    if (record.kind() != ValueKind::Typed || !eq(keyword(record.keyword_id()), name)) continue;
    Value list = typed_child(record);
    if (list.is_list()) return items(list);
  }
  return std::nullopt;
}

double Model::as_real(Value v) const {
  if (!v.is_number()) return std::nan("");
  const std::string_view s = slice(v);
  double result = 0;
  const char* begin = s.data();
  if (!s.empty() && s.front() == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, s.data() + s.size(), result);
  if (ec == std::errc::result_out_of_range) return 0.0;  // underflow; overflow was rejected on read
  if (ec != std::errc()) return std::nan("");
  return result;
}

std::int64_t Model::as_integer(Value v) const {
  if (v.kind() == ValueKind::Real) return static_cast<std::int64_t>(as_real(v));
  if (v.kind() != ValueKind::Integer) return 0;
  const std::string_view s = slice(v);
  std::int64_t result = 0;
  const char* begin = s.data();
  if (!s.empty() && s.front() == '+') ++begin;
  std::from_chars(begin, s.data() + s.size(), result);
  return result;
}

void Model::append_string(Value v, std::string& out) const {
  if (v.kind() != ValueKind::String) return;
  if (!v.needs_decoding()) {
    out += slice(v);
    return;
  }
  decode_string(slice(v), out);
}

std::string Model::as_string(Value v) const {
  std::string out;
  append_string(v, out);
  return out;
}

std::optional<Logical> Model::as_logical(Value v) const {
  if (v.kind() != ValueKind::Enumeration) return std::nullopt;
  const std::string_view e = slice(v);
  if (e == "T" || e == "t") return Logical::True;
  if (e == "F" || e == "f") return Logical::False;
  if (e == "U" || e == "u") return Logical::Unknown;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------

ModelBuilder::ModelBuilder(std::string text, std::size_t expected_values,
                           std::size_t expected_instances) {
  *model_.text_ = std::move(text);
  // Reserving the upper bound up front means the arenas never reallocate while reading, so
  // peak memory is not doubled by a copy; pages that are never touched cost no memory.
  model_.values_.reserve(expected_values);
  model_.instances_.reserve(expected_instances);
  advise_huge_pages(model_.values_.data(), model_.values_.capacity() * sizeof(Value));
  advise_huge_pages(model_.instances_.data(), model_.instances_.capacity() * sizeof(Instance));
  intern("(complex)");
  intern("(external reference)");
}

KeywordId ModelBuilder::intern(std::string_view name) {
  auto it = model_.keyword_index_.find(name);
  if (it != model_.keyword_index_.end()) return it->second;
  const auto id = static_cast<KeywordId>(model_.keywords_.size());
  const std::string& stored = model_.keyword_names_.emplace_back(name);
  model_.keywords_.push_back(stored);
  model_.keyword_index_.emplace(stored, id);
  return id;
}

std::uint32_t ModelBuilder::append_text(std::string_view text) {
  const auto offset = static_cast<std::uint32_t>(model_.text_->size());
  model_.text_->append(text);
  return offset;
}

std::uint32_t ModelBuilder::push_values(std::span<const Value> values) {
  const auto first = static_cast<std::uint32_t>(model_.values_.size());
  // Most lists are short (a point's three coordinates); a plain loop beats a memmove call.
  for (Value v : values) model_.values_.push_back(v);
  return first;
}

void ModelBuilder::append(Model&& part) {
  auto& m = model_;
  std::vector<KeywordId> keyword_of(part.keywords_.size());
  for (std::size_t k = 0; k < keyword_of.size(); ++k) keyword_of[k] = intern(part.keywords_[k]);
  const auto base = static_cast<std::uint32_t>(m.values_.size());
  for (Value v : part.values_) {
    if (v.kind() == ValueKind::List)
      v = Value::list(v.first() + base, v.count());
    else if (v.kind() == ValueKind::Typed)
      v = Value::typed(keyword_of[v.keyword_id()], v.child() + base);
    m.values_.push_back(v);
  }
  part.values_ = {};  // the memory back before the instances are copied: peak is one piece
  for (Instance instance : part.instances_) {
    instance.first += base;
    instance.keyword = keyword_of[instance.keyword];
    m.instances_.push_back(instance);
  }
  note_depth(part.max_depth_);
}

std::vector<ModelBuilder::DuplicateId> ModelBuilder::build_indexes() {
  std::vector<DuplicateId> duplicates;
  auto& m = model_;
  const auto count = static_cast<std::uint32_t>(m.instances_.size());
  std::uint64_t max_id = 0;
  for (const auto& inst : m.instances_) max_id = std::max(max_id, inst.id);

  m.dense_index_.clear();
  m.sparse_index_.clear();
  // Dense when the table would cost at most a few entries per instance.
  if (max_id <= std::uint64_t{4} * count + (1u << 20)) {
    m.dense_index_.assign(static_cast<std::size_t>(max_id) + 1, kNoInstance);
    for (std::uint32_t i = 0; i < count; ++i) {
      std::uint32_t& slot = m.dense_index_[m.instances_[i].id];
      if (slot == kNoInstance) {
        slot = i;
      } else {
        duplicates.push_back({slot, i});
      }
    }
  } else {
    m.sparse_index_.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) m.sparse_index_.emplace_back(m.instances_[i].id, i);
    std::stable_sort(m.sparse_index_.begin(), m.sparse_index_.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t out = 0;
    for (std::size_t i = 0; i < m.sparse_index_.size(); ++i) {
      if (out > 0 && m.sparse_index_[out - 1].first == m.sparse_index_[i].first) {
        duplicates.push_back({m.sparse_index_[out - 1].second, m.sparse_index_[i].second});
        continue;
      }
      m.sparse_index_[out++] = m.sparse_index_[i];
    }
    m.sparse_index_.resize(out);
  }

  // Group instance indices by keyword with a counting sort: linear, and file order is kept.
  const std::size_t keywords = m.keywords_.size();
  m.by_keyword_start_.assign(keywords + 1, 0);
  for (const auto& inst : m.instances_) ++m.by_keyword_start_[inst.keyword + 1];
  for (std::size_t k = 0; k < keywords; ++k) m.by_keyword_start_[k + 1] += m.by_keyword_start_[k];
  m.by_keyword_.resize(count);
  std::vector<std::uint32_t> cursor(m.by_keyword_start_.begin(), m.by_keyword_start_.end() - 1);
  for (std::uint32_t i = 0; i < count; ++i) m.by_keyword_[cursor[m.instances_[i].keyword]++] = i;
  return duplicates;
}

}  // namespace ncpost::p21
