#pragma once
// One call of an urn:ncpost:ext function (ext.cpp, ext_words.cpp): its arguments, its job, its
// errors and its one result. Internal to the XSLT stage.

#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>
#include <libxslt/extensions.h>
#include <libxslt/transform.h>
#include <libxslt/xsltutils.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ext_math.hpp"
#include "internal.hpp"

namespace ncpost::xslt::detail {

inline const xmlChar* name_of(const char* text) {
  return reinterpret_cast<const xmlChar*>(text);
}

// One call of an extension function: pops its arguments, reports errors against the
// stylesheet instruction, pushes exactly one result. A profile calls these functions several
// times per motion, so the common paths allocate nothing of their own: arguments sit in a
// fixed array, the job is found through ctxt->_private (xsltGetExtData is a hash look-up per
// call), numbers are read straight from a single attribute's text, strings are viewed in place.
class Call {
 public:
  static constexpr int kMaxArgs = 12;  // more than any function takes

  Call(xmlXPathParserContextPtr x, int nargs, const char* name, int min_args, int max_args)
      : x_(x), name_(name) {
    for (int n = nargs - 1; n >= 0; --n) {
      xmlXPathObjectPtr value = valuePop(x_);
      if (n < kMaxArgs)
        args_[static_cast<std::size_t>(n)] = value;
      else
        xmlXPathFreeObject(value);
    }
    count_ = static_cast<std::size_t>(std::clamp(nargs, 0, kMaxArgs));
    tctxt_ = xsltXPathGetTransformContext(x_);
    if (tctxt_ != nullptr) {
      // transform() puts its run there; a context it did not start is not ours.
      auto* run = static_cast<TransformRun*>(tctxt_->_private);
      if (run != nullptr && run->ctxt == tctxt_) run_ = run;
    }
    if (run_ == nullptr) {
      fail("needs a transform started by ncpost::xslt::transform()");
    } else if (nargs < min_args || nargs > max_args) {
      fail(min_args == max_args
               ? "takes " + std::to_string(min_args) + " argument(s), not " + std::to_string(nargs)
               : "takes " + std::to_string(min_args) + " to " + std::to_string(max_args) +
                     " arguments, not " + std::to_string(nargs));
    }
  }
  ~Call() {
    for (std::size_t n = 0; n < count_; ++n) xmlXPathFreeObject(args_[n]);
    for (xmlChar* text : casts_)
      if (text != nullptr) xmlFree(text);
    if (!pushed_) valuePush(x_, xmlXPathNewCString(""));
  }
  Call(const Call&) = delete;
  Call& operator=(const Call&) = delete;

  [[nodiscard]] bool ok() const noexcept { return !failed_; }
  [[nodiscard]] std::size_t count() const noexcept { return count_; }
  JobState& job() { return *run_->job; }
  const JobConfig& config() { return run_->job->config(); }

  double number(std::size_t n, const char* what) {
    const double v = to_number(args_[n]);
    if (!failed_ && !std::isfinite(v)) fail(std::string(what) + " is not a finite number");
    return v;
  }
  std::string string(std::size_t n) { return std::string(view(n)); }
  // The string value of argument n, valid until the call ends.
  std::string_view view(std::size_t n) {
    xmlXPathObjectPtr a = args_[n];
    if (a == nullptr) return {};
    const xmlChar* text = nullptr;
    if (a->type == XPATH_STRING) {
      text = a->stringval;
    } else {
      if (casts_[n] == nullptr) casts_[n] = xmlXPathCastToString(a);
      text = casts_[n];
    }
    return text != nullptr ? std::string_view(reinterpret_cast<const char*>(text)) : "";
  }
  [[nodiscard]] bool is_string(std::size_t n) const {
    return args_[n] != nullptr && args_[n]->type == XPATH_STRING;
  }

  void fail(const std::string& message) {
    if (failed_) return;
    failed_ = true;
    if (tctxt_ == nullptr) return;
    xsltTransformError(tctxt_, nullptr, tctxt_->inst, "ext:%s: %s\n", name_, message.c_str());
    tctxt_->state = XSLT_STATE_STOPPED;  // the first ext error ends the job; no cascade
  }
  void warn(diag::Code code, const std::string& message) {
    if (run_ == nullptr || run_->collector == nullptr) return;
    const Location where = location_of(tctxt_ != nullptr ? tctxt_->inst : nullptr);
    run_->collector->add(code, where.file, where.line, 0,
                         std::string("ext:") + name_ + ": " + message);
  }

  // The string is copied once, by length: xmlXPathNewString would measure it byte by byte
  // first, and a motion run's blocks are kilobytes.
  void push_string(const std::string& s) {
    if (pushed_) return;
    auto* copy = static_cast<xmlChar*>(xmlMalloc(s.size() + 1));
    if (copy == nullptr) throw std::bad_alloc();  // guarded() stops the transform
    std::memcpy(copy, s.c_str(), s.size() + 1);
    pushed_ = true;
    valuePush(x_, xmlXPathWrapString(copy));
  }
  // Pushes argument n back as the result when it is a string already (no copy).
  void push_argument(std::size_t n) {
    if (pushed_) return;
    if (!is_string(n)) {
      push_string(std::string(view(n)));
      return;
    }
    pushed_ = true;
    valuePush(x_, args_[n]);
    args_[n] = nullptr;
  }
  void push_number(double v) {
    if (pushed_) return;
    pushed_ = true;
    valuePush(x_, xmlXPathNewFloat(v));
  }
  // A node-set of <point x=".." y=".." z=".."/> elements in a result tree fragment that lives
  // as long as the instruction (or the variable that holds it), as EXSLT's str:tokenize does.
  void push_points(const std::vector<Point3>& points) {
    if (pushed_ || tctxt_ == nullptr) return;
    xmlDocPtr container = xsltCreateRVT(tctxt_);
    if (container == nullptr) return;
    xsltRegisterLocalRVT(tctxt_, container);
    xmlXPathObjectPtr set = xmlXPathNewNodeSet(nullptr);
    if (set == nullptr) return;
    for (const Point3& p : points) {
      xmlNodePtr node = xmlNewDocNode(container, nullptr, name_of("point"), nullptr);
      if (node == nullptr) break;
      xmlNewProp(node, name_of("x"), name_of(shortest(p.x).c_str()));
      xmlNewProp(node, name_of("y"), name_of(shortest(p.y).c_str()));
      xmlNewProp(node, name_of("z"), name_of(shortest(p.z).c_str()));
      xmlAddChild(reinterpret_cast<xmlNodePtr>(container), node);
      xmlXPathNodeSetAddUnique(set->nodesetval, node);
    }
    pushed_ = true;
    valuePush(x_, set);
  }

 private:
  // As xmlXPathCastToNumber, without its copy of the text when the argument is one attribute
  // (a coordinate: @x), which is what profiles pass almost always.
  static double to_number(xmlXPathObjectPtr a) {
    if (a == nullptr) return std::nan("");
    if (a->type == XPATH_NUMBER) return a->floatval;
    if (a->type == XPATH_NODESET && a->nodesetval != nullptr && a->nodesetval->nodeNr == 1) {
      const xmlNode* node = a->nodesetval->nodeTab[0];
      if (node != nullptr && node->type == XML_ATTRIBUTE_NODE && node->children != nullptr &&
          node->children->next == nullptr && node->children->type == XML_TEXT_NODE &&
          node->children->content != nullptr) {
        return xmlXPathStringEvalNumber(node->children->content);
      }
    }
    return xmlXPathCastToNumber(a);
  }

  xmlXPathParserContextPtr x_;
  const char* name_;
  std::array<xmlXPathObjectPtr, kMaxArgs> args_{};
  std::size_t count_ = 0;
  std::array<xmlChar*, kMaxArgs> casts_{};  // string values of non-string arguments
  xsltTransformContextPtr tctxt_ = nullptr;
  TransformRun* run_ = nullptr;
  bool failed_ = false;
  bool pushed_ = false;
};

// No C++ exception may cross libxml2's C frames: an allocation failure inside a function
// ends the job like any other error of the function.
template <void (*F)(xmlXPathParserContextPtr, int)>
void guarded(xmlXPathParserContextPtr x, int nargs) noexcept {
  try {
    F(x, nargs);
  } catch (...) {
    xsltTransformContextPtr t = xsltXPathGetTransformContext(x);
    if (t != nullptr) {
      xsltTransformError(t, nullptr, t->inst, "ext: internal error (out of memory)\n");
      t->state = XSLT_STATE_STOPPED;
    }
  }
}

struct Function {
  const char* name;
  xmlXPathFunction function;
};
// The block-level functions of ext_words.cpp, registered with the others.
[[nodiscard]] std::span<const Function> word_functions();

// ext:block(): the next block number by the job's rules (wrapping past the maximum).
inline std::int64_t next_block_number(JobState& job) {
  const BlockNumbers& rules = job.config().block;
  std::int64_t& next = Access::next_block(job);
  if (next > rules.maximum || next < rules.start) next = rules.start;
  const std::int64_t current = next;
  next = current > rules.maximum - rules.increment ? rules.start : current + rules.increment;
  return current;
}

// ext:modal()'s memory: whether `word` differs from the group's last word (then it is
// remembered); nothing, with the call failed, when a new group would pass the limit.
inline std::optional<bool> update_modal(Call& call, std::string_view group, std::string_view word) {
  auto& modal = Access::modal(call.job());
  const auto found = modal.find(group);
  if (found != modal.end()) {
    if (found->second == word) return false;
    found->second = word;
    return true;
  }
  if (modal.size() >= call.config().max_modal_groups) {
    call.fail("more than " + std::to_string(call.config().max_modal_groups) + " modal groups");
    return std::nullopt;
  }
  modal.emplace(std::string(group), std::string(word));
  return true;
}

// ext:line()'s check: a warning (the text is kept) when the block is longer than the
// controller takes.
inline void check_line_length(Call& call, std::string_view text) {
  const std::size_t limit = call.config().max_line_length;
  if (limit == 0 || text.size() <= limit) return;  // never more characters than bytes
  const std::size_t length = characters(text);
  if (length > limit) {
    call.warn(diag::Code::XsltLineTooLong,
              "block of " + std::to_string(length) + " characters; the controller takes " +
                  std::to_string(limit) + ": " + std::string(text.substr(0, 80)));
  }
}

// A block written in place into `out`: begin_block_line() writes the N word when the profile
// numbers its blocks ("N<next> ") and returns where the block starts; the caller appends the
// words; end_block_line() checks the block against the line length. No newline.
inline std::size_t begin_block_line(Call& call, std::string& out, bool numbered) {
  const std::size_t start = out.size();
  if (numbered) {
    char word[24];
    word[0] = 'N';
    char* end = std::to_chars(word + 1, word + sizeof word - 1, next_block_number(call.job())).ptr;
    *end++ = ' ';
    out.append(word, static_cast<std::size_t>(end - word));
  }
  return start;
}

inline void end_block_line(Call& call, const std::string& out, std::size_t start) {
  check_line_length(call, std::string_view(out).substr(start));
}

// Appends `text` as one block (ext:block-line).
inline void append_block_line(Call& call, std::string& out, std::string_view text, bool numbered) {
  const std::size_t start = begin_block_line(call, out, numbered);
  out += text;
  end_block_line(call, out, start);
}

}  // namespace ncpost::xslt::detail
