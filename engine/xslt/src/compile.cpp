// compile() and compile_text(): parse the stylesheet safely, let libxslt compile it (imports
// go through the loader in runtime.cpp), and collect what went wrong.

#include <libxslt/imports.h>
#include <libxslt/xslt.h>
#include <libxslt/xsltutils.h>

#include <optional>

#include "internal.hpp"

namespace ncpost::xslt {

namespace fs = std::filesystem;

CompiledStylesheet::CompiledStylesheet(void* style, fs::path file, std::vector<fs::path> files,
                                       std::string method)
    : style_(style), file_(std::move(file)), files_(std::move(files)), method_(std::move(method)) {}

CompiledStylesheet::~CompiledStylesheet() {
  // Frees the documents of the stylesheet and its imports as well.
  xsltFreeStylesheet(static_cast<xsltStylesheetPtr>(style_));
}

namespace {

CompileResult compile_impl(const std::optional<std::string_view>& text, const fs::path& file,
                           std::span<const fs::path> allowed_roots, const Limits& limits) {
  CompileResult result;
  if (!initialised()) {
    result.diagnostics.push_back(
        FileDiagnostic{file.string(), diag::make(diag::Code::XsltNotInitialised, 0, 0,
                                                 "call ncpost::xslt::initialise() at start-up")});
    return result;
  }
  std::error_code ec;
  fs::path absolute = fs::absolute(file, ec);
  if (ec) absolute = file;
  absolute = fs::weakly_canonical(absolute, ec);
  if (ec) absolute = fs::absolute(file, ec);

  detail::Collector collector(detail::Phase::Compile, limits.max_diagnostics, absolute.string());
  detail::CompileScope scope;
  scope.limits = &limits;
  scope.collector = &collector;
  for (const fs::path& root : allowed_roots) {
    const fs::path real = fs::canonical(root, ec);
    if (!ec && fs::is_directory(real, ec)) scope.roots.push_back(real);
  }

  xsltStylesheetPtr style = nullptr;
  {
    detail::ErrorScope errors(collector);
    detail::enter_compile(scope);
    xmlDocPtr doc = nullptr;
    if (text) {
      if (!detail::inside(absolute, scope.roots)) {
        collector.add(diag::Code::XsltImportRefused, absolute.string(), 0, 0,
                      "the stylesheet lies outside the profile folder and stylesheets/common/");
      } else if (text->size() > limits.max_stylesheet_bytes) {
        collector.add(diag::Code::XsltStylesheetLimit, absolute.string(), 0, 0,
                      "stylesheet of " + std::to_string(text->size()) + " bytes; the limit is " +
                          std::to_string(limits.max_stylesheet_bytes));
      } else {
        scope.files.push_back(absolute);
        doc = detail::parse_stylesheet_text(*text, absolute.string(), nullptr);
      }
    } else {
      doc = detail::load_stylesheet_file(absolute, nullptr, detail::Location{});
    }
    if (doc != nullptr) {
      style = xsltParseStylesheetDoc(doc);
      if (style == nullptr) {
        xmlFreeDoc(doc);  // libxslt leaves the document to the caller when it fails
      } else if (style->errors != 0) {
        xsltFreeStylesheet(style);
        style = nullptr;
      }
    }
    detail::leave_compile(scope);
    collector.finish();
  }
  if (style != nullptr) {
    // libxslt reports its warnings (unknown xsl:output method, unknown instruction kept for
    // forwards compatibility, ...) with the same "compilation error" prefix as errors; it
    // compiled without counting an error, so what it said were warnings.
    for (FileDiagnostic& d : collector.items()) {
      if (d.diagnostic.code == diag::Code::XsltStylesheetInvalid) {
        d.diagnostic.code = diag::Code::XsltStylesheetWarning;
        d.diagnostic.severity = diag::Severity::Warning;
      }
    }
  }
  if (style != nullptr && (scope.refused || collector.has_errors())) {
    xsltFreeStylesheet(style);
    style = nullptr;
  }
  if (style == nullptr && !collector.has_errors()) {
    collector.add(diag::Code::XsltStylesheetInvalid, absolute.string(), 0, 0,
                  "the stylesheet did not compile");
  }
  result.diagnostics = std::move(collector.items());
  if (style == nullptr) return result;

  const xmlChar* method = nullptr;
  XSLT_GET_IMPORT_PTR(method, style, method)
  std::string method_name = method != nullptr ? reinterpret_cast<const char*>(method) : "xml";
  fs::path main = scope.files.empty() ? absolute : scope.files.front();
  result.stylesheet =
      Access::make(style, std::move(main), std::move(scope.files), std::move(method_name));
  return result;
}

}  // namespace

CompileResult compile(const fs::path& file, std::span<const fs::path> allowed_roots,
                      const Limits& limits) {
  return compile_impl(std::nullopt, file, allowed_roots, limits);
}

CompileResult compile_text(std::string_view text, const fs::path& as_file,
                           std::span<const fs::path> allowed_roots, const Limits& limits) {
  return compile_impl(text, as_file, allowed_roots, limits);
}

}  // namespace ncpost::xslt
