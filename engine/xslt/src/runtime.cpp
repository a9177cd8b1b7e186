// Process-wide set-up (initialise), the counting allocator behind the memory and time limits,
// the error channels, the security preferences and the import loader.
//
// libxslt keeps three things process-wide: the generic error function, the document loader and
// the default security preferences. Each is installed once here, with a function that looks up
// what belongs to the calling thread (its current Collector, CompileScope or Budget) in a
// thread_local, so concurrent jobs never see each other's errors. libxml2's error callbacks are
// per thread already; ErrorScope installs and restores them around each compile or transform.

#include <libexslt/exslt.h>
#include <libxml/parser.h>
#include <libxml/uri.h>
#include <libxml/xmlmemory.h>
#include <libxslt/documents.h>
#include <libxslt/security.h>
#include <libxslt/xslt.h>
#include <libxslt/xsltutils.h>
#include <malloc.h>

#include <array>
#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>

#include "internal.hpp"

namespace ncpost::xslt {
namespace detail {
namespace {

namespace fs = std::filesystem;

thread_local Collector* t_collector = nullptr;
thread_local Budget* t_budget = nullptr;
thread_local CompileScope* t_compile = nullptr;

std::atomic<bool> g_initialised{false};
xsltSecurityPrefsPtr g_security = nullptr;

// ---- counting allocator ----------------------------------------------------------------
// Wraps malloc and friends; when a Budget is active on this thread, live bytes are counted
// (malloc_usable_size, so frees need no header) and the budget may trip. Never fails an
// allocation itself: libxml2 2.9 does not recover from every failed malloc, so the stop goes
// through libxslt's own operation counters instead.

void trip(Budget& b, Budget::Trip why) noexcept {
  if (b.tripped != Budget::Trip::None) return;
  b.tripped = why;
  if (t_collector != nullptr) b.diagnostics_at_trip = t_collector->items().size();
  if (b.ctxt == nullptr) return;
  // Only pointers and counters are touched here (no allocation inside the allocator): the
  // instruction is a stylesheet node, valid as long as the compiled stylesheet.
  xsltTransformContextPtr ctxt = b.ctxt;
  b.where = ctxt->inst;
  if (ctxt->opLimit == 0) ctxt->opLimit = 1;
  ctxt->opCount = ctxt->opLimit;  // the next instruction stops the transform
  if (ctxt->xpathCtxt != nullptr) {
    ctxt->xpathCtxt->opLimit = 1;  // the next XPath operation fails
    ctxt->xpathCtxt->opCount = 1;
  }
}

void account_alloc(Budget& b, std::size_t usable) noexcept {
  b.live += usable;
  if (b.live > b.peak) b.peak = b.live;
  if (b.max_bytes != 0 && b.live > b.max_bytes) trip(b, Budget::Trip::Memory);
  if ((b.has_deadline || b.cancel != nullptr) && (++b.ticks & 255u) == 0) {
    if (b.cancel != nullptr && b.cancel->load(std::memory_order_relaxed))
      trip(b, Budget::Trip::Cancelled);
    else if (b.has_deadline && std::chrono::steady_clock::now() > b.deadline)
      trip(b, Budget::Trip::Time);
  }
}

void account_free(Budget& b, std::size_t usable) noexcept {
  b.live = usable > b.live ? 0 : b.live - usable;
}

// A per-thread cache of freed small blocks, by glibc's size classes. A transform allocates and
// frees hundreds of small objects per motion (nodes, XPath objects, strings) in bursts larger
// than glibc's own per-thread cache (7 blocks per size), so most of them went through glibc's
// slower paths: about a quarter of a transform's instructions. Blocks stay glibc blocks (any
// thread may free or realloc them), a block handed out has exactly the usable size glibc would
// give for the request (so the accounting is unchanged), and the cache is bounded. Off under
// AddressSanitizer, which must see every free, and ThreadSanitizer, which would take a block
// that one thread cached and another reused for a race.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kBlockCache = false;
#else
constexpr bool kBlockCache = true;
#endif

class BlockCache {
 public:
  BlockCache() = default;
  BlockCache(const BlockCache&) = delete;
  BlockCache& operator=(const BlockCache&) = delete;
  ~BlockCache() {
    for (Node*& head : heads_) {
      while (head != nullptr) {
        Node* n = head;
        head = n->next;
        std::free(n);
      }
    }
    bytes_ = kMaxBytes;  // a free after this (another thread_local's destructor) goes to glibc
  }

  // A cached block for a request of `size` bytes, with its usable size; null if none.
  void* take(std::size_t size, std::size_t& usable) noexcept {
    const std::size_t c = size <= kMinUsable ? 0 : (size - kMinUsable + kStep - 1) / kStep;
    if (c >= kClasses || heads_[c] == nullptr) return nullptr;
    Node* n = heads_[c];
    heads_[c] = n->next;
    usable = kMinUsable + c * kStep;
    bytes_ -= usable;
    return n;
  }
  // Keeps a block being freed, if it is small and the cache has room.
  bool keep(void* p, std::size_t usable) noexcept {
    if (usable < kMinUsable || (usable - kMinUsable) % kStep != 0) return false;
    const std::size_t c = (usable - kMinUsable) / kStep;
    if (c >= kClasses || bytes_ + usable > kMaxBytes) return false;
    auto* n = static_cast<Node*>(p);
    n->next = heads_[c];
    heads_[c] = n;
    bytes_ += usable;
    return true;
  }

 private:
  struct Node {
    Node* next;
  };
  // glibc (64-bit): chunks of 32, 48, 64, ... bytes, usable 8 bytes less.
  static constexpr std::size_t kMinUsable = 24;
  static constexpr std::size_t kStep = 16;
  static constexpr std::size_t kClasses = 32;                       // usable sizes up to 520 bytes
  static constexpr std::size_t kMaxBytes = std::size_t{256} << 10;  // per thread
  std::array<Node*, kClasses> heads_{};
  std::size_t bytes_ = 0;
};

thread_local BlockCache t_blocks;

void* counting_malloc(std::size_t size) {
  std::size_t usable = 0;
  void* p = kBlockCache ? t_blocks.take(size, usable) : nullptr;
  if (p == nullptr) {
    p = std::malloc(size);
    if (p == nullptr) return nullptr;
    if (t_budget == nullptr) return p;
    usable = malloc_usable_size(p);
  }
  if (t_budget != nullptr) account_alloc(*t_budget, usable);
  return p;
}

void* counting_realloc(void* old, std::size_t size) {
  Budget* b = t_budget;
  if (b != nullptr && old != nullptr) account_free(*b, malloc_usable_size(old));
  void* p = std::realloc(old, size);
  if (b != nullptr) {
    if (p != nullptr) {
      account_alloc(*b, malloc_usable_size(p));
    } else if (old != nullptr) {
      b->live += malloc_usable_size(old);  // the old block is still there
    }
  }
  return p;
}

void counting_free(void* p) {
  if (p == nullptr) return;
  if (!kBlockCache && t_budget == nullptr) {
    std::free(p);
    return;
  }
  const std::size_t usable = malloc_usable_size(p);
  if (t_budget != nullptr) account_free(*t_budget, usable);
  if (!kBlockCache || !t_blocks.keep(p, usable)) std::free(p);
}

char* counting_strdup(const char* s) {
  const std::size_t n = std::strlen(s) + 1;
  auto* p = static_cast<char*>(counting_malloc(n));
  if (p != nullptr) std::memcpy(p, s, n);
  return p;
}

// ---- error channels ----------------------------------------------------------------------

// libxslt's process-wide generic error function (installed once).
__attribute__((format(printf, 2, 3))) void xslt_generic(void*, const char* fmt, ...) {
  Collector* c = t_collector;
  if (c == nullptr) return;  // outside any compile or transform: nobody to tell
  va_list args;
  va_start(args, fmt);
  try {
    c->generic_text(vformat(fmt, args));
  } catch (...) {  // no exception may cross libxslt's C frames; the message is lost
  }
  va_end(args);
}

// libxml2's generic channel (per thread, installed by ErrorScope).
__attribute__((format(printf, 2, 3))) void xml_generic(void* context, const char* fmt, ...) {
  auto* c = static_cast<Collector*>(context);
  if (c == nullptr) return;
  va_list args;
  va_start(args, fmt);
  try {
    c->generic_text(vformat(fmt, args));
  } catch (...) {
  }
  va_end(args);
}

void xml_structured(void* context, xmlErrorPtr error) {
  auto* c = static_cast<Collector*>(context);
  try {
    if (c != nullptr && error != nullptr) c->libxml_error(*error);
  } catch (...) {
  }
}

// ---- paths and security ------------------------------------------------------------------

// The local path a URI names, or nothing for URLs of other schemes, remote hosts, queries and
// fragments. libxslt hands the loader URIs it built with xmlBuildURI against the base.
std::optional<fs::path> local_path(const char* uri_text) {
  if (uri_text == nullptr || *uri_text == '\0') return std::nullopt;
  xmlURIPtr uri = xmlParseURI(uri_text);
  if (uri == nullptr) return std::nullopt;
  std::optional<fs::path> result;
  const bool file_scheme = uri->scheme == nullptr || std::strcmp(uri->scheme, "file") == 0;
  const bool local_host = uri->server == nullptr || uri->server[0] == '\0' ||
                          std::strcmp(uri->server, "localhost") == 0;
  if (file_scheme && local_host && uri->opaque == nullptr && uri->query == nullptr &&
      uri->query_raw == nullptr && uri->fragment == nullptr && uri->path != nullptr) {
    result = fs::path(uri->path);
  }
  xmlFreeURI(uri);
  return result;
}

std::optional<fs::path> real_path(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::canonical(p, ec);
  if (ec) return std::nullopt;
  return c;
}

// Records where the xsl:import and xsl:include elements of a freshly parsed stylesheet point.
void record_references(xmlDocPtr doc, CompileScope& scope) {
  const xmlNode* root = xmlDocGetRootElement(doc);
  if (root == nullptr) return;
  static const xmlChar* const kXslt =
      reinterpret_cast<const xmlChar*>("http://www.w3.org/1999/XSL/Transform");
  for (const xmlNode* n = root->children; n != nullptr; n = n->next) {
    if (n->type != XML_ELEMENT_NODE || n->ns == nullptr || !xmlStrEqual(n->ns->href, kXslt))
      continue;
    if (!xmlStrEqual(n->name, reinterpret_cast<const xmlChar*>("import")) &&
        !xmlStrEqual(n->name, reinterpret_cast<const xmlChar*>("include"))) {
      continue;
    }
    xmlChar* href = xmlGetNsProp(n, reinterpret_cast<const xmlChar*>("href"), nullptr);
    if (href == nullptr) continue;
    xmlChar* base = xmlNodeGetBase(doc, n);
    xmlChar* uri = xmlBuildURI(href, base);
    if (uri != nullptr) {
      const Location where = location_of(n);
      const std::string text = reinterpret_cast<const char*>(uri);
      scope.references.emplace(text, where);
      if (const std::optional<fs::path> path = local_path(text.c_str()))
        scope.references.emplace(path->string(), where);
    }
    xmlFree(uri);
    xmlFree(base);
    xmlFree(href);
  }
}

Location reference_to(const std::string& uri_or_path) {
  CompileScope* scope = t_compile;
  if (scope == nullptr) return {};
  const auto found = scope->references.find(uri_or_path);
  return found != scope->references.end() ? found->second : Location{};
}

// Where an import may be read from: its real path, or why not. Outside is judged before
// existence, so a refusal does not tell whether a file exists elsewhere.
struct Resolved {
  std::optional<fs::path> path;
  std::string why;
};

Resolved resolve_import(const fs::path& p, const std::vector<fs::path>& roots) {
  std::error_code ec;
  const fs::path lexical = fs::weakly_canonical(p, ec);
  if (ec || !inside(lexical, roots)) {
    return {std::nullopt, "refused: it lies outside the profile folder and stylesheets/common/"};
  }
  const std::optional<fs::path> real = real_path(p);
  if (!real) return {std::nullopt, "cannot be read: no such file"};
  if (!inside(*real, roots)) {
    return {std::nullopt, "refused: it lies outside the profile folder and stylesheets/common/"};
  }
  return {real, {}};
}

// What a refusal reports: our own diagnostic, clearer than libxslt's, which follows and is
// dropped by the collector (refusals_reported).
void report_refusal(xsltTransformContextPtr ctxt, diag::Code code, std::string message,
                    const Location& at = {}) {
  Collector* c = t_collector;
  if (c == nullptr) return;
  const Location where = ctxt != nullptr ? location_of(ctxt->inst) : at;
  c->add(code, where.file, where.line, 0, std::move(message));
  c->refusal_reported();
}

// READ_FILE. Compile time (no transform context): only files inside the compile's roots (the
// loader checks again and reads). Transform time: only the stylesheet's own file, which
// libxslt then serves from memory (the document('') idiom); the loader reads nothing.
int check_read_file_impl(xsltTransformContextPtr ctxt, const char* value) {
  const std::string path = value != nullptr ? value : "";
  if (ctxt == nullptr) {
    CompileScope* scope = t_compile;
    if (scope == nullptr) return 0;
    const Resolved resolved = resolve_import(fs::path(path), scope->roots);
    if (resolved.path) return 1;
    scope->refused = true;
    report_refusal(nullptr, diag::Code::XsltImportRefused, "'" + path + "' " + resolved.why,
                   reference_to(path));
    return 0;
  }
  if (ctxt->style != nullptr && ctxt->style->doc != nullptr && ctxt->style->doc->URL != nullptr) {
    const std::optional<fs::path> own =
        local_path(reinterpret_cast<const char*>(ctxt->style->doc->URL));
    if (own && *own == fs::path(path)) return 1;
  }
  report_refusal(ctxt, diag::Code::XsltAccessRefused,
                 "reading '" + path + "' refused: a stylesheet may not read files (document())");
  return 0;
}

int check_read_network_impl(xsltTransformContextPtr ctxt, const char* value) {
  const std::string url = value != nullptr ? value : "";
  if (ctxt == nullptr) {
    if (t_compile != nullptr) t_compile->refused = true;
    report_refusal(nullptr, diag::Code::XsltImportRefused,
                   "'" + url +
                       "' refused: imports and includes must be files in the profile folder or "
                       "stylesheets/common/, not URLs",
                   reference_to(url));
  } else {
    report_refusal(ctxt, diag::Code::XsltAccessRefused,
                   "reading '" + url + "' refused: a stylesheet may not use the network");
  }
  return 0;
}

int check_write_impl(xsltTransformContextPtr ctxt, const char* value) {
  report_refusal(
      ctxt, diag::Code::XsltAccessRefused,
      "writing '" + std::string(value != nullptr ? value : "") +
          "' refused: a stylesheet may not write files, create folders or use the network "
          "(exsl:document, xsl:document)");
  return 0;
}

// The document loader libxslt calls for the main stylesheet, imports and includes, and
// document(). Only the first three read files, and only through the compile's checks.
xmlDocPtr loader_impl(const xmlChar* uri, xmlDictPtr dict, void* ctxt, xsltLoadType type) {
  const char* text = reinterpret_cast<const char*>(uri);
  if (type == XSLT_LOAD_DOCUMENT) {
    // The security preferences stop document() before this; this is the second wall. The
    // stylesheet's own URL returns nothing so that libxslt falls back to the parsed stylesheet.
    auto* tctxt = static_cast<xsltTransformContextPtr>(ctxt);
    bool own = false;
    if (tctxt != nullptr && tctxt->style != nullptr && tctxt->style->doc != nullptr &&
        tctxt->style->doc->URL != nullptr && text != nullptr) {
      own = std::strcmp(reinterpret_cast<const char*>(tctxt->style->doc->URL), text) == 0;
    }
    if (!own) {
      report_refusal(tctxt, diag::Code::XsltAccessRefused,
                     std::string("reading '") + (text ? text : "") +
                         "' refused: a stylesheet may not read files");
    }
    return nullptr;
  }
  CompileScope* scope = t_compile;
  if (scope == nullptr || scope->collector == nullptr) return nullptr;
  // The xsl:import / xsl:include element that asks (recorded when its file was parsed).
  Location referrer = reference_to(text != nullptr ? text : "");
  if (referrer.file.empty() && type == XSLT_LOAD_STYLESHEET && ctxt != nullptr) {
    auto* style = static_cast<xsltStylesheetPtr>(ctxt);  // the importing stylesheet
    if (style->doc != nullptr && style->doc->URL != nullptr) {
      referrer.file = reinterpret_cast<const char*>(style->doc->URL);
    }
  }
  const std::optional<fs::path> path = local_path(text);
  if (!path || !path->is_absolute()) {
    scope->refused = true;
    scope->collector->add(
        diag::Code::XsltImportRefused, referrer.file, referrer.line, 0,
        std::string("'") + (text ? text : "") +
            "' refused: imports and includes must be files in the profile folder or "
            "stylesheets/common/, not URLs");
    scope->collector->refusal_reported();
    return nullptr;
  }
  return load_stylesheet_file(*path, dict, referrer);
}

// The C entry points: no exception may cross libxslt's frames; a failure refuses.
int check_read_file(xsltSecurityPrefsPtr, xsltTransformContextPtr ctxt,
                    const char* value) noexcept {
  try {
    return check_read_file_impl(ctxt, value);
  } catch (...) {
    return 0;
  }
}

int check_read_network(xsltSecurityPrefsPtr, xsltTransformContextPtr ctxt,
                       const char* value) noexcept {
  try {
    return check_read_network_impl(ctxt, value);
  } catch (...) {
    return 0;
  }
}

int check_write(xsltSecurityPrefsPtr, xsltTransformContextPtr ctxt, const char* value) noexcept {
  try {
    return check_write_impl(ctxt, value);
  } catch (...) {
    return 0;
  }
}

xmlDocPtr loader(const xmlChar* uri, xmlDictPtr dict, int, void* ctxt, xsltLoadType type) noexcept {
  try {
    return loader_impl(uri, dict, ctxt, type);
  } catch (...) {
    return nullptr;
  }
}

}  // namespace

std::string vformat(const char* fmt, va_list args) {
  char small[512];
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(small, sizeof small, fmt, copy);
  va_end(copy);
  if (n < 0) return {};
  if (static_cast<std::size_t>(n) < sizeof small)
    return std::string(small, static_cast<std::size_t>(n));
  std::string big(static_cast<std::size_t>(n) + 1, '\0');
  std::vsnprintf(big.data(), big.size(), fmt, args);
  big.resize(static_cast<std::size_t>(n));
  return big;
}

Location location_of(const xmlNode* node) {
  Location l;
  if (node == nullptr) return l;
  if (node->doc != nullptr && node->doc->URL != nullptr) {
    l.file = reinterpret_cast<const char*>(node->doc->URL);
  }
  const long line = xmlGetLineNo(node);
  if (line > 0) l.line = static_cast<std::uint32_t>(line);
  return l;
}

bool inside(const fs::path& canonical_path, const std::vector<fs::path>& roots) {
  for (const fs::path& root : roots) {
    auto r = root.begin();
    auto p = canonical_path.begin();
    for (; r != root.end() && p != canonical_path.end(); ++r, ++p) {
      if (*r != *p) break;
    }
    // A trailing empty component (root spelled with a final '/') matches anything.
    while (r != root.end() && r->empty()) ++r;
    if (r == root.end()) return true;
  }
  return false;
}

xmlDocPtr parse_stylesheet_text(std::string_view text, const std::string& url, xmlDictPtr dict) {
  xmlParserCtxtPtr pctxt = xmlNewParserCtxt();
  if (pctxt == nullptr) return nullptr;
  if (dict != nullptr) {
    // Share libxslt's dictionary, as its default loader does, so imported names intern alike.
    if (pctxt->dict != nullptr) xmlDictFree(pctxt->dict);
    pctxt->dict = dict;
    xmlDictReference(dict);
  }
  xmlDocPtr doc = xmlCtxtReadMemory(pctxt, text.data(), static_cast<int>(text.size()), url.c_str(),
                                    nullptr, kParseOptions);
  xmlFreeParserCtxt(pctxt);
  if (doc == nullptr) return nullptr;
  if (doc->intSubset == nullptr && doc->extSubset == nullptr && t_compile != nullptr) {
    record_references(doc, *t_compile);
  }
  if (doc->intSubset != nullptr || doc->extSubset != nullptr) {
    if (t_collector != nullptr) {
      t_collector->add(
          diag::Code::XsltDtdRefused, url, 0, 0,
          "a stylesheet may not have a DOCTYPE (no entity is expanded); use character references");
    }
    xmlFreeDoc(doc);
    return nullptr;
  }
  return doc;
}

xmlDocPtr load_stylesheet_file(const fs::path& path, xmlDictPtr dict, const Location& referrer) {
  CompileScope* scope = t_compile;
  if (scope == nullptr || scope->collector == nullptr) return nullptr;
  Collector& c = *scope->collector;
  const auto refuse = [&](diag::Code code, std::string message) -> xmlDocPtr {
    scope->refused = true;
    c.add(code, referrer.file, referrer.line, 0, std::move(message));
    c.refusal_reported();
    return nullptr;
  };
  const Resolved resolved = resolve_import(path, scope->roots);
  if (!resolved.path)
    return refuse(diag::Code::XsltImportRefused, "'" + path.string() + "' " + resolved.why);
  const fs::path& real = *resolved.path;
  if (scope->files.size() >= scope->limits->max_stylesheet_files) {
    return refuse(diag::Code::XsltStylesheetLimit,
                  "more than " + std::to_string(scope->limits->max_stylesheet_files) +
                      " stylesheet files (imports and includes); limit reached at '" +
                      real.string() + "'");
  }
  std::error_code ec;
  if (!fs::is_regular_file(real, ec)) {
    return refuse(diag::Code::XsltImportRefused,
                  "'" + real.string() + "' cannot be read: not a regular file");
  }
  const auto size = fs::file_size(real, ec);
  if (ec) return refuse(diag::Code::XsltImportRefused, "'" + real.string() + "' cannot be read");
  if (size > scope->limits->max_stylesheet_bytes) {
    return refuse(diag::Code::XsltStylesheetLimit,
                  "'" + real.string() + "' has " + std::to_string(size) + " bytes; the limit is " +
                      std::to_string(scope->limits->max_stylesheet_bytes));
  }
  std::ifstream in(real, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) return refuse(diag::Code::XsltImportRefused, "'" + real.string() + "' cannot be read");
  scope->files.push_back(real);
  return parse_stylesheet_text(bytes.str(), real.string(), dict);
}

void enter_compile(CompileScope& scope) noexcept {
  scope.previous = t_compile;
  t_compile = &scope;
}

void leave_compile(CompileScope& scope) noexcept {
  t_compile = scope.previous;
}

xsltSecurityPrefsPtr security_prefs() noexcept {
  return g_security;
}

ErrorScope::ErrorScope(Collector& collector)
    : previous_(t_collector),
      previous_structured_(xmlStructuredError),
      previous_structured_context_(xmlStructuredErrorContext),
      previous_generic_(xmlGenericError),
      previous_generic_context_(xmlGenericErrorContext) {
  t_collector = &collector;
  xmlSetStructuredErrorFunc(&collector, xml_structured);
  xmlSetGenericErrorFunc(&collector, xml_generic);
}

ErrorScope::~ErrorScope() {
  t_collector = previous_;
  xmlSetStructuredErrorFunc(previous_structured_context_, previous_structured_);
  xmlSetGenericErrorFunc(previous_generic_context_, previous_generic_);
}

BudgetScope::BudgetScope(Budget& budget) : previous_(t_budget) {
  t_budget = &budget;
}
BudgetScope::~BudgetScope() {
  t_budget = previous_;
}

}  // namespace detail

void initialise() {
  static std::once_flag once;
  std::call_once(once, [] {
    using namespace detail;
    // The allocator first: libxml2 allocates from here on. Memory that other code got from
    // libxml2 before is plain malloc memory, which counting_free releases just as well.
    xmlMemSetup(counting_free, counting_malloc, counting_realloc, counting_strdup);
    xmlInitParser();
    xsltInit();
    exsltRegisterAll();

    g_security = xsltNewSecurityPrefs();
    xsltSetSecurityPrefs(g_security, XSLT_SECPREF_READ_FILE, check_read_file);
    xsltSetSecurityPrefs(g_security, XSLT_SECPREF_WRITE_FILE, check_write);
    xsltSetSecurityPrefs(g_security, XSLT_SECPREF_CREATE_DIRECTORY, check_write);
    xsltSetSecurityPrefs(g_security, XSLT_SECPREF_READ_NETWORK, check_read_network);
    xsltSetSecurityPrefs(g_security, XSLT_SECPREF_WRITE_NETWORK, check_write);
    xsltSetDefaultSecurityPrefs(g_security);

    xsltSetLoaderFunc(loader);
    xsltSetGenericErrorFunc(nullptr, xslt_generic);
    register_extensions();
    g_initialised.store(true, std::memory_order_release);
  });
}

bool initialised() noexcept {
  return detail::g_initialised.load(std::memory_order_acquire);
}

}  // namespace ncpost::xslt
