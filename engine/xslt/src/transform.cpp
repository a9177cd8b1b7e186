// transform(): one job's (or chunk's) run of a shared compiled stylesheet, in the order of
// libxslt's xsltproc.c: parse the input, new transform context, security preferences, limits,
// parameters, xsltApplyStylesheetUser, check ctxt->state, serialize, free.

#include <libxml/parser.h>
#include <libxslt/imports.h>
#include <libxslt/security.h>
#include <libxslt/transform.h>
#include <libxslt/variables.h>
#include <libxslt/xsltutils.h>

#include <algorithm>
#include <climits>
#include <cstdarg>

#include "internal.hpp"

namespace ncpost::xslt {

JobState::JobState(JobConfig config, Limits limits)
    : config_(std::move(config)), limits_(limits), next_block_(config_.block.start) {}

void JobState::set_run_motions(std::span<const RunMotion> motions) {
  run_motions_ = motions;
  run_rendered_.assign(motions.size(), 0);
}

std::size_t JobState::run_motions_not_rendered() const noexcept {
  return static_cast<std::size_t>(std::count(run_rendered_.begin(), run_rendered_.end(), 0));
}

void JobState::reset() {
  next_block_ = config_.block.start;
  modal_.clear();
  program_unit_mm_ = 1.0;
  last_c_ = 0.0;
  position_ = {0, 0, 0};
  has_position_ = false;
}

namespace {

using detail::Collector;

// The transform context's own error channel: run-time errors and xsl:message.
__attribute__((format(printf, 2, 3))) void transform_error(void* context, const char* fmt, ...) {
  auto* run = static_cast<detail::TransformRun*>(context);
  if (run == nullptr || run->collector == nullptr) return;
  va_list args;
  va_start(args, fmt);
  try {
    run->collector->transform_text(detail::vformat(fmt, args), run->ctxt);
  } catch (...) {  // no exception may cross libxslt's C frames; the message is lost
  }
  va_end(args);
}

std::string mib(std::size_t bytes) {
  return std::to_string((bytes + (std::size_t{1} << 19)) >> 20) + " MiB";
}

bool any_code(const std::vector<FileDiagnostic>& items, diag::Code code) {
  return std::any_of(items.begin(), items.end(),
                     [code](const FileDiagnostic& d) { return d.diagnostic.code == code; });
}

// Where the document comes from: XML text to parse, or a tree built in memory.
struct Source {
  std::string_view xml;
  const InputTree* tree = nullptr;
};

// Whether libxslt would strip whitespace text from the input, which frees input nodes.
bool strips_whitespace(xsltStylesheetPtr style) {
  for (xsltStylesheetPtr s = style; s != nullptr; s = xsltNextImport(s))
    if (s->stripSpaces != nullptr || s->stripAll != 0) return true;
  return false;
}

TransformResult run(const CompiledStylesheet& stylesheet, Source source, JobState& job,
                    const Params& params, std::string_view input_name) {
  const std::string_view xml = source.xml;
  TransformResult result;
  const std::string sheet_file = stylesheet.file().string();
  const std::string input(input_name);
  if (!initialised()) {
    result.diagnostics.push_back(
        FileDiagnostic{sheet_file, diag::make(diag::Code::XsltNotInitialised, 0, 0,
                                              "call ncpost::xslt::initialise() at start-up")});
    return result;
  }
  const Limits& limits = job.limits();
  Collector collector(detail::Phase::Transform, limits.max_diagnostics, sheet_file, input);
  if (xml.size() > limits.max_input_bytes || xml.size() > static_cast<std::size_t>(INT_MAX)) {
    collector.add(diag::Code::XsltInputXml, input, 0, 0,
                  "document of " + std::to_string(xml.size()) + " bytes; the limit is " +
                      std::to_string(std::min<std::size_t>(limits.max_input_bytes, INT_MAX)));
    result.diagnostics = std::move(collector.items());
    return result;
  }

  if (job.cancel() != nullptr && job.cancel()->load(std::memory_order_relaxed)) {
    result.cancelled = true;  // nothing parsed, nothing run
    return result;
  }
  detail::Budget budget;
  budget.max_bytes = limits.max_memory;
  if (limits.max_time.count() > 0) {
    budget.has_deadline = true;
    budget.deadline = std::chrono::steady_clock::now() + limits.max_time;
  }
  budget.cancel = job.cancel();
  detail::TransformRun run{&job, &collector, nullptr};
  xsltStylesheetPtr style = Access::style(stylesheet);

  xsltTransformState state = XSLT_STATE_ERROR;
  bool produced = false;
  bool step_limit_hit = false;
  bool xpath_limit_hit = false;
  const xmlNode* last_inst = nullptr;
  bool tripped_in_parse = false;
  {
    detail::ErrorScope errors(collector);
    detail::BudgetScope accounting(budget);
    xmlDocPtr doc = nullptr;
    if (source.tree == nullptr) {
      doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), input.c_str(), nullptr,
                          detail::kParseOptions);
    } else if (!source.tree->complete()) {
      collector.add(diag::Code::XsltInputXml, input, 0, 0,
                    "the document built in memory has no root element, or an unclosed one");
    } else {
      doc = detail::lend_tree(*source.tree, input);
    }
    if (source.tree == nullptr && doc != nullptr &&
        (doc->intSubset != nullptr || doc->extSubset != nullptr)) {
      collector.add(diag::Code::XsltDtdRefused, input, 0, 0,
                    "the document has a DOCTYPE; none is accepted");
      xmlFreeDoc(doc);
      doc = nullptr;
    }
    if (source.tree == nullptr && doc != nullptr && budget.tripped != detail::Budget::Trip::None) {
      tripped_in_parse = true;  // the document alone is over the budget: do not start
      xmlFreeDoc(doc);
      doc = nullptr;
    }
    if (doc == nullptr && !collector.has_errors() && !tripped_in_parse) {
      collector.add(diag::Code::XsltInputXml, input, 0, 0, "the document could not be parsed");
    }
    xsltTransformContextPtr ctxt = doc != nullptr ? xsltNewTransformContext(style, doc) : nullptr;
    if (ctxt != nullptr) {
      run.ctxt = ctxt;
      ctxt->_private = &run;
      collector.set_transform_context(ctxt);
      xsltSetCtxtSecurityPrefs(detail::security_prefs(), ctxt);
      xsltSetTransformErrorFunc(ctxt, &run, transform_error);
      xsltSetCtxtParseOptions(ctxt, detail::kParseOptions);
      ctxt->maxTemplateDepth = limits.max_template_depth;
      ctxt->maxTemplateVars = limits.max_template_vars;
      ctxt->opLimit = static_cast<unsigned long>(limits.max_steps);
      ctxt->opCount = 0;
      if (ctxt->xpathCtxt != nullptr) {
        ctxt->xpathCtxt->opLimit = static_cast<unsigned long>(limits.max_xpath_ops);
        ctxt->xpathCtxt->opCount = 0;
      }
      std::vector<const char*> flat;
      flat.reserve(params.size() * 2 + 1);
      for (const auto& [name, value] : params) {
        flat.push_back(name.c_str());
        flat.push_back(value.c_str());
      }
      flat.push_back(nullptr);
      if (!params.empty()) xsltQuoteUserParams(ctxt, flat.data());

      budget.ctxt = ctxt;
      // A trip while the context was made (no context yet to stop) means: do not start.
      xmlDocPtr out = budget.tripped == detail::Budget::Trip::None
                          ? xsltApplyStylesheetUser(style, doc, nullptr, nullptr, nullptr, ctxt)
                          : nullptr;
      state = ctxt->state;
      step_limit_hit = ctxt->opLimit != 0 && ctxt->opCount >= ctxt->opLimit;
      xpath_limit_hit = ctxt->xpathCtxt != nullptr && ctxt->xpathCtxt->opLimit != 0 &&
                        ctxt->xpathCtxt->opCount >= ctxt->xpathCtxt->opLimit;
      last_inst = ctxt->inst;
      if (out != nullptr && state == XSLT_STATE_OK &&
          budget.tripped == detail::Budget::Trip::None) {
        xmlChar* text = nullptr;
        int length = 0;
        if (xsltSaveResultToString(&text, &length, out, style) == 0) {
          produced = true;
          if (text != nullptr && length > 0)
            result.output.assign(reinterpret_cast<const char*>(text),
                                 static_cast<std::size_t>(length));
        }
        xmlFree(text);
      }
      budget.ctxt = nullptr;
      collector.set_transform_context(nullptr);
      xmlFreeDoc(out);
      xsltFreeTransformContext(ctxt);
    }
    if (source.tree != nullptr)
      detail::take_back_tree(*source.tree, doc);
    else
      xmlFreeDoc(doc);
    collector.finish();
  }

  std::vector<FileDiagnostic>& items = collector.items();
  // libxslt's texts name its own command-line options; say which Limits field was reached.
  for (FileDiagnostic& d : items) {
    std::string& m = d.diagnostic.message;
    const std::size_t in = m.rfind(" [in ");
    const std::string element = in != std::string::npos ? m.substr(in) : std::string();
    switch (d.diagnostic.code) {
      case diag::Code::XsltDepthLimit:
        m = "templates and instructions nested deeper than " +
            std::to_string(limits.max_template_depth) +
            " (max_template_depth): endless recursion?" + element;
        break;
      case diag::Code::XsltVariableLimit:
        m = "more than " + std::to_string(limits.max_template_vars) +
            " live variables and parameters (max_template_vars)" + element;
        break;
      case diag::Code::XsltStepLimit:
        m = "more than " + std::to_string(limits.max_steps) +
            " XSLT instructions (max_steps); stopped" + element;
        break;
      case diag::Code::XsltXPathLimit:
        m = "more than " + std::to_string(limits.max_xpath_ops) +
            " XPath operations (max_xpath_ops); stopped" + element;
        break;
      default:
        break;
    }
  }
  if (budget.tripped != detail::Budget::Trip::None) {
    // Errors reported after the trip are consequences of the stop (operation counters
    // exhausted on purpose); the limit itself is the one error that matters.
    std::vector<FileDiagnostic> kept;
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (i < budget.diagnostics_at_trip || items[i].diagnostic.severity != diag::Severity::Error) {
        kept.push_back(std::move(items[i]));
      }
    }
    if (budget.tripped == detail::Budget::Trip::Cancelled) {
      // Whoever cancelled the job knows why; the stylesheet did nothing wrong.
      result.cancelled = true;
      result.output.clear();  // the trip may have come while the result was serialised
      result.diagnostics = std::move(kept);
      return result;
    }
    const detail::Location where = detail::location_of(budget.where);
    const bool memory = budget.tripped == detail::Budget::Trip::Memory;
    const std::string what = tripped_in_parse ? "parsing the document" : "the transform";
    FileDiagnostic limit{
        tripped_in_parse     ? input
        : where.file.empty() ? sheet_file
                             : where.file,
        memory ? diag::make(diag::Code::XsltMemoryLimit, where.line, 0,
                            what + " used more than " + mib(limits.max_memory) +
                                " of memory (max_memory); stopped")
               : diag::make(diag::Code::XsltTimeLimit, where.line, 0,
                            what + " took longer than " + std::to_string(limits.max_time.count()) +
                                " ms (max_time); stopped")};
    kept.insert(kept.begin(), std::move(limit));
    items = std::move(kept);
  } else {
    const detail::Location where = detail::location_of(last_inst);
    if (step_limit_hit && !any_code(items, diag::Code::XsltStepLimit)) {
      items.insert(items.begin(),
                   FileDiagnostic{where.file.empty() ? sheet_file : where.file,
                                  diag::make(diag::Code::XsltStepLimit, where.line, 0,
                                             "more than " + std::to_string(limits.max_steps) +
                                                 " XSLT instructions (max_steps); stopped")});
    } else if (xpath_limit_hit && !any_code(items, diag::Code::XsltXPathLimit)) {
      items.insert(items.begin(),
                   FileDiagnostic{where.file.empty() ? sheet_file : where.file,
                                  diag::make(diag::Code::XsltXPathLimit, where.line, 0,
                                             "more than " + std::to_string(limits.max_xpath_ops) +
                                                 " XPath operations (max_xpath_ops); stopped")});
    }
  }
  if (state == XSLT_STATE_STOPPED && !diag::has_errors(items)) {
    auto message = std::find_if(items.rbegin(), items.rend(), [](const FileDiagnostic& d) {
      return d.diagnostic.code == diag::Code::XsltMessage;
    });
    FileDiagnostic stop{sheet_file, diag::make(diag::Code::XsltTerminated, 0, 0,
                                               "the stylesheet stopped the transform")};
    if (message != items.rend()) {
      stop.file = message->file;
      stop.diagnostic.line = message->diagnostic.line;
      stop.diagnostic.message += ": " + message->diagnostic.message;
    }
    items.push_back(std::move(stop));
  }
  if ((state != XSLT_STATE_OK || (!produced && result.output.empty())) &&
      !diag::has_errors(items)) {
    std::string message = "the transform failed";
    if (!collector.side_text().empty()) message += ": " + collector.side_text();
    while (!message.empty() && message.back() == '\n') message.pop_back();
    items.push_back(FileDiagnostic{
        sheet_file, diag::make(diag::Code::XsltRuntimeError, 0, 0, std::move(message))});
  }
  result.ok = state == XSLT_STATE_OK && produced && budget.tripped == detail::Budget::Trip::None &&
              !diag::has_errors(items);
  if (!result.ok) result.output.clear();
  result.diagnostics = std::move(items);
  return result;
}

}  // namespace

TransformResult transform(const CompiledStylesheet& stylesheet, std::string_view xml, JobState& job,
                          const Params& params, std::string_view input_name) {
  return run(stylesheet, Source{xml, nullptr}, job, params, input_name);
}

TransformResult transform(const CompiledStylesheet& stylesheet, const InputTree& tree,
                          JobState& job, const Params& params, std::string_view input_name) {
  if (initialised() && strips_whitespace(Access::style(stylesheet))) {
    const std::string xml = tree.to_xml();
    return run(stylesheet, Source{xml, nullptr}, job, params, input_name);
  }
  return run(stylesheet, Source{{}, &tree}, job, params, input_name);
}

}  // namespace ncpost::xslt
