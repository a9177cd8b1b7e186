// Turns libxslt's printf-style error output and libxml2's structured errors into
// FileDiagnostics (see Collector in internal.hpp).

#include <libxml/xmlerror.h>

#include <algorithm>
#include <charconv>

#include "internal.hpp"

namespace ncpost::xslt {

namespace detail {
namespace {

constexpr std::size_t kMaxSideText = 4096;
constexpr std::size_t kMaxMessage = 2000;

bool contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

// Lines joined by spaces, without trailing blanks; bounded, so a hostile message stays short.
std::string tidy(std::string_view text) {
  std::string out;
  out.reserve(std::min(text.size(), kMaxMessage));
  bool space = false;
  for (const char ch : text) {
    if (ch == '\n' || ch == '\r' || ch == '\t' || ch == ' ') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += ch;
    if (out.size() >= kMaxMessage) {
      out += "...";
      break;
    }
  }
  return out;
}

std::uint32_t to_line(std::string_view digits) {
  std::uint32_t value = 0;
  std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return value;
}

bool is_limit(diag::Code code) {
  switch (code) {
    case diag::Code::XsltDepthLimit:
    case diag::Code::XsltVariableLimit:
    case diag::Code::XsltStepLimit:
    case diag::Code::XsltXPathLimit:
    case diag::Code::XsltMemoryLimit:
    case diag::Code::XsltTimeLimit:
      return true;
    default:
      return false;
  }
}

}  // namespace

Collector::Collector(Phase phase, std::size_t max, std::string default_file, std::string input_name)
    : phase_(phase),
      max_(max),
      default_file_(std::move(default_file)),
      input_name_(std::move(input_name)) {}

void Collector::add(diag::Code code, std::string file, std::uint32_t line, std::uint32_t column,
                    std::string message, std::optional<diag::Severity> severity) {
  if (items_.size() >= max_) {
    ++dropped_;
    return;
  }
  diag::Diagnostic d = diag::make(code, line, column, std::move(message));
  if (severity) d.severity = *severity;
  if (file.empty()) file = default_file_;
  if (!items_.empty()) {  // the same error repeated back to back (libxml2 does that) counts once
    const FileDiagnostic& last = items_.back();
    if (last.file == file && last.diagnostic.code == d.code && last.diagnostic.line == d.line &&
        last.diagnostic.column == d.column && last.diagnostic.message == d.message) {
      return;
    }
  }
  items_.push_back(FileDiagnostic{std::move(file), std::move(d)});
}

bool Collector::has_errors() const noexcept {
  return diag::has_errors(items_);
}

void Collector::generic_text(std::string_view text) {
  generic_partial_.append(text);
  if (!generic_partial_.empty() && generic_partial_.back() == '\n') {
    std::string unit_text;
    unit_text.swap(generic_partial_);
    unit(std::move(unit_text), false, nullptr);
  } else if (generic_partial_.size() > 64 * 1024) {
    generic_partial_.resize(64 * 1024);
  }
}

void Collector::transform_text(std::string_view text, const xsltTransformContext* ctxt) {
  transform_partial_.append(text);
  if (!transform_partial_.empty() && transform_partial_.back() == '\n') {
    std::string unit_text;
    unit_text.swap(transform_partial_);
    unit(std::move(unit_text), true, ctxt);
  } else if (transform_partial_.size() > 64 * 1024) {
    transform_partial_.resize(64 * 1024);
  }
}

// One complete piece of libxslt output: an error context line or a message.
void Collector::unit(std::string text, bool transform_channel, const xsltTransformContext* ctxt) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::string_view rest;
  bool warning = false;
  // xsltPrintErrorContext: "<type>[: file F[ line N][ element E]]" or "<type>[: element E]".
  for (const std::string_view type :
       {std::string_view("runtime error"), std::string_view("compilation error"),
        std::string_view("compilation warning"), std::string_view("error"),
        std::string_view("warning")}) {
    if (text.size() >= type.size() && text.compare(0, type.size(), type) == 0 &&
        text.find('\n') == std::string::npos &&
        (text.size() == type.size() || text.compare(type.size(), 7, ": file ") == 0 ||
         text.compare(type.size(), 10, ": element ") == 0)) {
      rest = std::string_view(text).substr(type.size());
      warning = type == "compilation warning" || type == "warning";
      Context context;
      context.warning = warning;
      if (rest.size() >= 2) rest.remove_prefix(2);
      if (rest.substr(0, 5) == "file ") {
        rest.remove_prefix(5);
        const std::size_t element = rest.rfind(" element ");
        if (element != std::string_view::npos) {
          context.element = std::string(rest.substr(element + 9));
          rest = rest.substr(0, element);
        }
        const std::size_t line = rest.rfind(" line ");
        if (line != std::string_view::npos) {
          context.line = to_line(rest.substr(line + 6));
          rest = rest.substr(0, line);
        }
        context.file = std::string(rest);
      } else if (rest.substr(0, 8) == "element ") {
        context.element = std::string(rest.substr(8));
      }
      if (pending_) message("(no message)", transform_channel, ctxt);
      pending_ = std::move(context);
      return;
    }
  }
  message(std::move(text), transform_channel, ctxt);
}

void Collector::message(std::string text, bool transform_channel,
                        const xsltTransformContext* ctxt) {
  std::string body = tidy(text);
  if (pending_) {
    Context context = std::move(*pending_);
    pending_.reset();
    diag::Code code = classify(body);
    if (follow_up(code, body)) {
      FileDiagnostic& ours = items_[*refusal_index_];
      if (ours.diagnostic.line == 0 && context.line != 0) {
        ours.file = context.file.empty() ? ours.file : context.file;
        ours.diagnostic.line = context.line;
      }
      return;
    }
    if (pending_xpath_) {
      if (is_limit(pending_xpath_->code) && !is_limit(code)) code = pending_xpath_->code;
      body += " (XPath: " + pending_xpath_->text + ")";
      pending_xpath_.reset();
    }
    if (!context.element.empty()) body += " [in " + context.element + "]";
    std::optional<diag::Severity> severity;
    if (context.warning) {
      if (phase_ == Phase::Compile) {
        code = diag::Code::XsltStylesheetWarning;
      } else {
        severity = diag::Severity::Warning;
      }
    }
    add(code, context.file, context.line, 0, std::move(body), severity);
    return;
  }
  if (body.empty()) return;
  if (transform_channel) {
    // A transform context's channel without a context line: the text of an xsl:message.
    const Location where = ctxt != nullptr ? location_of(ctxt->inst) : Location{};
    add(diag::Code::XsltMessage, where.file, where.line, 0, std::move(body));
    return;
  }
  if (follow_up(classify(body), body)) return;
  if (phase_ == Phase::Transform) {
    // libxslt's debug dumps (template and variable stacks after a recursion error) and the
    // like: kept aside, used only if nothing else explains a failure.
    if (side_.size() < kMaxSideText) side_ += body.substr(0, kMaxSideText - side_.size()) + "\n";
    return;
  }
  const diag::Code code = classify(body);
  add(code, {}, 0, 0, std::move(body));
}

bool Collector::follow_up(diag::Code code, std::string_view message) const {
  if (!refusal_index_ || *refusal_index_ >= items_.size()) return false;
  return code == diag::Code::XsltImportRefused || code == diag::Code::XsltAccessRefused ||
         contains(message, "unable to load") || contains(message, "failed to load") ||
         contains(message, "could not load") || contains(message, "failed to compute");
}

diag::Code Collector::classify(std::string_view message) const {
  if (phase_ == Phase::Compile) {
    if (contains(message, "refused") || contains(message, "denied"))
      return diag::Code::XsltImportRefused;
    if (message.substr(0, 7) == "Warning" || message.substr(0, 7) == "warning" ||
        contains(message, " warning:")) {
      return diag::Code::XsltStylesheetWarning;
    }
    return diag::Code::XsltStylesheetInvalid;
  }
  if (contains(message, "infinite") && contains(message, "recursion")) {
    return contains(message, "maxTemplateVars") || contains(message, "--maxvars")
               ? diag::Code::XsltVariableLimit
               : diag::Code::XsltDepthLimit;
  }
  if (contains(message, "Operation limit exceeded")) return diag::Code::XsltStepLimit;
  if (contains(message, "refused") || contains(message, "denied"))
    return diag::Code::XsltAccessRefused;
  if (message.substr(0, 4) == "ext:") return diag::Code::XsltExtArgument;
  return diag::Code::XsltRuntimeError;
}

void Collector::libxml_error(const xmlError& error) {
  std::string text = tidy(error.message != nullptr ? error.message : "unknown libxml2 error");
  const bool warning = error.level == XML_ERR_WARNING;
  const auto column = static_cast<std::uint32_t>(std::max(error.int2, 0));
  const auto line = static_cast<std::uint32_t>(std::max(error.line, 0));
  switch (error.domain) {
    case XML_FROM_XPATH:
    case XML_FROM_XPOINTER: {
      diag::Code code = phase_ == Phase::Compile ? diag::Code::XsltStylesheetInvalid
                                                 : diag::Code::XsltRuntimeError;
      if (contains(text, "Operation limit exceeded")) code = diag::Code::XsltXPathLimit;
      if (contains(text, "Recursion") || contains(text, "recursion"))
        code = diag::Code::XsltDepthLimit;
      if (error.str1 != nullptr) text += " in '" + tidy(error.str1) + "'";
      if (pending_xpath_ && pending_xpath_->code == code && pending_xpath_->text == text)
        return;  // re-raised
      flush_xpath();
      // libxslt usually follows with the stylesheet location; keep the detail for that message.
      pending_xpath_ = PendingXPath{code, std::move(text),
                                    ctxt_ != nullptr ? location_of(ctxt_->inst) : Location{}};
      return;
    }
    case XML_FROM_PARSER:
    case XML_FROM_NAMESPACE:
    case XML_FROM_DTD:
    case XML_FROM_VALID:
    case XML_FROM_HTML:
    case XML_FROM_CHECK: {
      const std::optional<diag::Severity> severity =
          warning ? std::optional<diag::Severity>(diag::Severity::Warning) : std::nullopt;
      if (phase_ == Phase::Compile) {
        add(warning ? diag::Code::XsltStylesheetWarning : diag::Code::XsltStylesheetXml,
            error.file != nullptr ? error.file : std::string(), line, column, std::move(text),
            severity);
      } else {
        add(diag::Code::XsltInputXml, input_name_, line, column, std::move(text), severity);
      }
      return;
    }
    case XML_FROM_IO:
    case XML_FROM_URI:
      add(phase_ == Phase::Compile ? diag::Code::XsltImportRefused : diag::Code::XsltAccessRefused,
          error.file != nullptr ? error.file : std::string(), line, column, std::move(text));
      return;
    default:
      if (warning) return;  // nothing a profile author could act on
      add(phase_ == Phase::Compile ? diag::Code::XsltStylesheetInvalid
                                   : diag::Code::XsltRuntimeError,
          error.file != nullptr ? error.file : std::string(), line, column, std::move(text));
      return;
  }
}

void Collector::flush_xpath() {
  if (!pending_xpath_) return;
  PendingXPath p = std::move(*pending_xpath_);
  pending_xpath_.reset();
  add(p.code, std::move(p.where.file), p.where.line, 0, "XPath: " + p.text);
}

void Collector::finish() {
  if (!generic_partial_.empty()) {
    std::string rest;
    rest.swap(generic_partial_);
    unit(std::move(rest), false, nullptr);
  }
  if (!transform_partial_.empty()) {
    std::string rest;
    rest.swap(transform_partial_);
    unit(std::move(rest), true, nullptr);
  }
  if (pending_) message("(no message)", false, nullptr);
  flush_xpath();
  if (dropped_ > 0) {
    const std::size_t dropped = dropped_;
    dropped_ = 0;
    ++max_;  // room for the note itself
    add(diag::Code::XsltTooManyDiagnostics, {}, 0, 0,
        std::to_string(dropped) + " further diagnostics dropped (limit " +
            std::to_string(max_ - 1) + ")");
  }
}

}  // namespace detail
}  // namespace ncpost::xslt
