#pragma once
// The instance graph of one ISO 10303-21 exchange structure.
//
// Memory layout (why it is this way: files can be hundreds of MB):
//  - the original text is kept, immutable, and values are slices of it;
//  - instances are 24-byte records in file order, sections are ranges of them;
//  - all parameter values live in one arena of 8-byte `Value`s. An instance's parameters are
//    `count` consecutive values starting at `first`; a list's children likewise;
//  - ids map to instances through a dense table when ids are dense, a sorted table otherwise;
//  - keywords (entity names) are interned, and instances are also indexed by keyword.
// A Model is built by a reader (P21 or P28) and is read-only afterwards, so any number of threads
// may read one Model at once.

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "ncpost/p21/value.hpp"

namespace ncpost::p21 {

using KeywordId = std::uint32_t;

struct Instance {
  std::uint64_t id = 0;      // 0 for header entities
  std::uint32_t offset = 0;  // where the instance starts in the text (for line:column)
  KeywordId keyword = 0;  // entity name; kComplexKeyword or kExternalKeyword for the special kinds
  std::uint32_t first = 0;  // first parameter in the value arena
  std::uint32_t count = 0;  // number of parameters (complex: partial records, each a Typed value)
};
static_assert(sizeof(Instance) == 24);

// An ed.3 DATA section: the instances [first_instance, end_instance), and the section's own
// parameters (name and schema) when it has them.
struct DataSection {
  std::uint32_t first_instance = 0;
  std::uint32_t end_instance = 0;
  std::uint32_t first_param = 0;
  std::uint32_t param_count = 0;
  std::uint32_t offset = 0;
};

// An ed.3 ANCHOR: `<name> = item;` (tags are skipped with a note).
struct Anchor {
  std::uint32_t name_offset = 0;
  std::uint32_t name_length = 0;
  Value item;
  std::uint32_t offset = 0;
};

enum class Logical : std::uint8_t { False, True, Unknown };

class ModelBuilder;

class Model {
 public:
  static constexpr KeywordId kComplexKeyword = 0;   // `(A(..) B(..))`
  static constexpr KeywordId kExternalKeyword = 1;  // ed.3 REFERENCE section entry `#n = <uri>;`

  Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;
  ~Model();

  // ---- the file ----
  [[nodiscard]] std::string_view text() const { return *text_; }
  [[nodiscard]] std::span<const Instance> header() const { return header_; }
  [[nodiscard]] std::span<const DataSection> sections() const { return sections_; }
  [[nodiscard]] std::span<const Anchor> anchors() const { return anchors_; }
  // All data instances (and REFERENCE entries) in file order.
  [[nodiscard]] std::span<const Instance> instances() const { return instances_; }
  [[nodiscard]] const Instance* header_entity(std::string_view keyword) const;

  // ---- look-ups ----
  [[nodiscard]] const Instance* find(std::uint64_t id) const;
  [[nodiscard]] std::optional<KeywordId> keyword_id(std::string_view name) const;  // any case
  [[nodiscard]] std::string_view keyword(KeywordId id) const { return keywords_[id]; }
  [[nodiscard]] std::size_t keyword_count() const { return keywords_.size(); }
  [[nodiscard]] std::string_view type_name(const Instance& instance) const {
    return keyword(instance.keyword);
  }
  [[nodiscard]] bool is_complex(const Instance& instance) const {
    return instance.keyword == kComplexKeyword;
  }
  // True when the instance has this entity name, or (complex) one of its partial records has it.
  [[nodiscard]] bool has_type(const Instance& instance, std::string_view name) const;
  // Instances whose keyword is `name` (simple instances only), in file order.
  [[nodiscard]] std::vector<const Instance*> instances_of(std::string_view name) const;
  [[nodiscard]] std::span<const std::uint32_t> instance_indices_of(KeywordId keyword) const;

  // ---- values ----
  [[nodiscard]] std::span<const Value> params(const Instance& instance) const {
    return {values_.data() + instance.first, instance.count};
  }
  // The parameters of one partial record of a complex instance, or nullopt when absent.
  [[nodiscard]] std::optional<std::span<const Value>> record_params(const Instance& instance,
                                                                    std::string_view name) const;
  [[nodiscard]] std::span<const Value> items(Value list) const {
    return {values_.data() + list.first(), list.count()};
  }
  [[nodiscard]] Value typed_child(Value typed) const { return values_[typed.child()]; }
  [[nodiscard]] std::span<const Value> all_values() const { return values_; }

  // Raw text of a slice value as it appears in the file (without delimiters).
  [[nodiscard]] std::string_view slice(Value v) const {
    return text().substr(v.offset(), v.length());
  }
  // Numbers were validated when read; these convert. Integers are accepted as reals.
  [[nodiscard]] double as_real(Value v) const;
  [[nodiscard]] std::int64_t as_integer(Value v) const;
  // The UTF-8 content of a string value, with all escapes decoded.
  [[nodiscard]] std::string as_string(Value v) const;
  void append_string(Value v, std::string& out) const;
  [[nodiscard]] std::string_view enumeration(Value v) const { return slice(v); }
  [[nodiscard]] std::optional<Logical> as_logical(Value v) const;

  // Largest list nesting depth in the model; readers keep it at or below their limit, which is
  // what makes recursive walks over values safe.
  [[nodiscard]] std::uint32_t max_depth() const { return max_depth_; }

 private:
  friend class ModelBuilder;

  // unique_ptr keeps the text's address stable when the Model moves: keyword views point into it.
  std::unique_ptr<std::string> text_;
  std::vector<Instance> header_;
  std::vector<Instance> instances_;
  std::vector<DataSection> sections_;
  std::vector<Anchor> anchors_;
  std::vector<Value> values_;

  // Keyword names are copied once each (there are few distinct ones), so the text may grow while
  // a model is built; a deque keeps each name's address stable for the index's views.
  std::deque<std::string> keyword_names_;
  std::vector<std::string_view> keywords_;
  struct CaseInsensitiveHash {
    std::size_t operator()(std::string_view s) const noexcept;
  };
  struct CaseInsensitiveEqual {
    bool operator()(std::string_view a, std::string_view b) const noexcept;
  };
  std::unordered_map<std::string_view, KeywordId, CaseInsensitiveHash, CaseInsensitiveEqual>
      keyword_index_;

  // id → instance index: dense when ids are dense, else sorted (id, index) pairs.
  std::vector<std::uint32_t> dense_index_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sparse_index_;

  // Instance indices grouped by keyword (counting sort): by_keyword_[start[k] .. start[k+1]).
  std::vector<std::uint32_t> by_keyword_;
  std::vector<std::uint32_t> by_keyword_start_;

  std::uint32_t max_depth_ = 0;
};

// Builds a Model. Used by the readers; also by tests and generators that make models in code.
// Values appended here must respect the layout contract: children before their parents, each
// instance's parameters contiguous.
class ModelBuilder {
 public:
  explicit ModelBuilder(std::string text, std::size_t expected_values = 0,
                        std::size_t expected_instances = 0);

  [[nodiscard]] std::string_view text() const { return *model_.text_; }
  KeywordId intern(std::string_view name);
  // Appends text (for example P21-escaped strings from another format) and returns its offset.
  std::uint32_t append_text(std::string_view text);
  // The text the values were read from, handed over by a reader that read it while it arrived
  // (StreamReader): replaces the (empty) text the builder was made with.
  void set_text(std::string text) { *model_.text_ = std::move(text); }

  std::uint32_t push_values(std::span<const Value> values);  // returns the index of the first
  void truncate_values(std::uint32_t count) { model_.values_.resize(count); }
  [[nodiscard]] std::uint32_t value_count() const {
    return static_cast<std::uint32_t>(model_.values_.size());
  }
  void add_header(const Instance& instance) { model_.header_.push_back(instance); }
  void add_instance(const Instance& instance) { model_.instances_.push_back(instance); }
  [[nodiscard]] std::uint32_t instance_count() const {
    return static_cast<std::uint32_t>(model_.instances_.size());
  }
  // Appends the instances of `part`, a model read from the piece of the same text that follows
  // (a file read in parallel), with its values renumbered into this arena and its keywords
  // into this table. `part` has instances only: no header, sections or anchors.
  void append(Model&& part);
  void add_section(const DataSection& section) { model_.sections_.push_back(section); }
  void add_anchor(const Anchor& anchor) { model_.anchors_.push_back(anchor); }
  void note_depth(std::uint32_t depth) {
    if (depth > model_.max_depth_) model_.max_depth_ = depth;
  }

  struct DuplicateId {
    std::uint32_t first_index;
    std::uint32_t duplicate_index;
  };
  // Builds the id and keyword indexes. Duplicate ids keep the first instance and are returned.
  [[nodiscard]] std::vector<DuplicateId> build_indexes();
  [[nodiscard]] Model finish() && { return std::move(model_); }
  [[nodiscard]] const Model& model() const { return model_; }

 private:
  Model model_;
};

}  // namespace ncpost::p21
