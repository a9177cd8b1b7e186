// write_xml(): the XML intermediate form (grammar engine/gcode/gcode.rng, docs/gcode.md "The
// XML form"). Blocks as the interpreter takes them — in execution order, so a loop's blocks
// come once per pass — each with its source line, its words and their evaluated values, the
// canonical calls it made and the diagnostics it raised. One block is held at a time and
// written whole: memory does not grow with the program.

#include <charconv>
#include <string>

#include "interpreter.hpp"
#include "ncpost/canon/xml.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "ncpost/xmltext/escape.hpp"

namespace ncpost::gcode {

namespace {

void attribute(std::string& out, std::string_view name, std::string_view value) {
  out += ' ';
  out += name;
  out += "=\"";
  xmltext::append_escaped(out, value, true);
  out += '"';
}

void attribute(std::string& out, std::string_view name, std::uint64_t value) {
  char buffer[24];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value);
  attribute(out, name, std::string_view(buffer, static_cast<std::size_t>(r.ptr - buffer)));
}

class XmlForm final : public detail::BlockObserver, public canon::Sink {
 public:
  XmlForm(const std::function<void(std::string_view)>& out, const Dialect& dialect,
          const ReadOptions& options)
      : out_(out) {
    std::string head =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<gcode-program format=\"ncpost-gcode\" "
        "version=\"1\"";
    attribute(head, "dialect", dialect.id);
    attribute(head, "name", options.program_name);
    head += ">\n";
    out_(head);
  }

  void begin_block(std::string_view file, std::uint32_t line, std::string_view raw) override {
    flush_outside();
    in_block_ = true;
    block_ = "<block";
    attribute(block_, "file", file);
    attribute(block_, "row", line);
    block_ += ">\n  <source>";
    xmltext::append_escaped(block_, raw);
    block_ += "</source>\n";
  }
  void word(std::string_view name, std::string_view text, double value,
            std::uint32_t column) override {
    block_ += "  <word";
    attribute(block_, "address", name);
    attribute(block_, "text", text);
    block_ += " value=\"";
    canon::append_xml_number(block_, value);
    block_ += '"';
    attribute(block_, "column", column);
    block_ += "/>\n";
  }
  void comment(std::string_view text, std::uint32_t column) override {
    block_ += "  <comment";
    attribute(block_, "column", column);
    block_ += '>';
    xmltext::append_escaped(block_, text);
    block_ += "</comment>\n";
  }
  void statement(std::string_view kind, std::string_view text) override {
    block_ += "  <statement";
    attribute(block_, "kind", kind);
    block_ += '>';
    xmltext::append_escaped(block_, text);
    block_ += "</statement>\n";
  }
  void end_block() override {
    close_calls(block_);
    block_ += errors_;
    block_ += "</block>\n";
    errors_.clear();
    in_block_ = false;
    out_(block_);
    block_.clear();
  }

  // The calls, inside the block that made them (or between blocks: the program's end).
  void call(const canon::Call& call) override {
    std::string& target = in_block_ ? block_ : outside_;
    if (!calls_open_) {
      target += in_block_ ? "  <calls>\n" : "<calls>\n";
      calls_open_ = true;
    }
    // A workingstep's begin and end stand in different blocks: both are empty elements here
    // (canon's chunk form makes a container of them).
    if (const auto* b = std::get_if<canon::Begin>(&call);
        b != nullptr && b->scope == canon::Scope::Workingstep) {
      target += "  <WORKINGSTEP_BEGIN";
      if (b->entity.id != 0) attribute(target, "id", b->entity.id);
      if (!b->entity.type.empty()) attribute(target, "type", b->entity.type);
      attribute(target, "name", b->entity.name);
      target += "/>\n";
      return;
    }
    canon::XmlChunkWriter writer;
    writer.append(target, std::span<const canon::Call>(&call, 1));
  }

  void diagnostic(const diag::FileDiagnostic& d) {
    std::string& target = in_block_ ? errors_ : outside_;
    if (!in_block_) close_calls(outside_);
    target += in_block_ ? "  <error" : "<error";
    attribute(target, "file", d.file);
    attribute(target, "row", d.diagnostic.line);
    attribute(target, "column", d.diagnostic.column);
    attribute(target, "code", d.diagnostic.code_id());
    attribute(target, "severity", diag::to_string(d.diagnostic.severity));
    target += '>';
    xmltext::append_escaped(target, d.diagnostic.message);
    target += "</error>\n";
  }

  void finish() {
    flush_outside();
    close_calls(outside_);
    outside_ += "</gcode-program>\n";
    out_(outside_);
  }

 private:
  void close_calls(std::string& target) {
    if (!calls_open_) return;
    target += in_block_ ? "  </calls>\n" : "</calls>\n";
    calls_open_ = false;
  }
  void flush_outside() {
    if (outside_.empty()) return;
    close_calls(outside_);
    out_(outside_);
    outside_.clear();
  }

  const std::function<void(std::string_view)>& out_;
  std::string block_;
  std::string errors_;
  std::string outside_;
  bool in_block_ = false;
  bool calls_open_ = false;
};

}  // namespace

ReadResult write_xml(std::string_view text, const Dialect& dialect,
                     const std::function<void(std::string_view)>& out, const ReadOptions& options) {
  XmlForm form(out, dialect, options);
  detail::Interpreter interpreter(text, dialect, form, options, &form);
  interpreter.on_diagnostic([&](const diag::FileDiagnostic& d) { form.diagnostic(d); });
  interpreter.run();
  form.finish();
  return std::move(interpreter).result();
}

}  // namespace ncpost::gcode
