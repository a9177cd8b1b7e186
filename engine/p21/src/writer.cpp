#include "ncpost/p21/writer.hpp"

namespace ncpost::p21 {
namespace {

constexpr std::size_t kFlushAt = 64 * 1024;

class Writer {
 public:
  Writer(const Model& model, const TextSink& sink) : model_(model), sink_(sink) {
    buffer_.reserve(kFlushAt + 4096);
  }

  void run() {
    put("ISO-10303-21;\nHEADER;\n");
    for (const Instance& h : model_.header()) {
      put(model_.type_name(h));
      params(model_.params(h));
      put(";\n");
    }
    put("ENDSEC;\n");
    if (!model_.anchors().empty()) {
      put("ANCHOR;\n");
      for (const Anchor& a : model_.anchors()) {
        put("<");
        put(model_.text().substr(a.name_offset, a.name_length));
        put(">=");
        append_value(model_, a.item, buffer_);
        put(";\n");
      }
      put("ENDSEC;\n");
    }
    bool any_external = false;
    for (const Instance& inst : model_.instances()) {
      if (inst.keyword != Model::kExternalKeyword) continue;
      if (!any_external) put("REFERENCE;\n");
      any_external = true;
      put("#");
      put(std::to_string(inst.id));
      put("=");
      append_value(model_, model_.params(inst)[0], buffer_);
      put(";\n");
    }
    if (any_external) put("ENDSEC;\n");
    for (const DataSection& section : model_.sections()) {
      put("DATA");
      if (section.param_count > 0)
        params(model_.all_values().subspan(section.first_param, section.param_count));
      put(";\n");
      for (std::uint32_t i = section.first_instance; i < section.end_instance; ++i) {
        const Instance& inst = model_.instances()[i];
        if (inst.keyword == Model::kExternalKeyword) continue;
        instance(inst);
      }
      put("ENDSEC;\n");
    }
    put("END-ISO-10303-21;\n");
    flush();
  }

 private:
  void put(std::string_view s) {
    buffer_ += s;
    if (buffer_.size() >= kFlushAt) flush();
  }
  void flush() {
    if (!buffer_.empty()) sink_(buffer_);
    buffer_.clear();
  }
  void params(std::span<const Value> values) {
    buffer_ += '(';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) buffer_ += ',';
      append_value(model_, values[i], buffer_);
    }
    buffer_ += ')';
  }
  void instance(const Instance& inst) {
    buffer_ += '#';
    buffer_ += std::to_string(inst.id);
    buffer_ += '=';
    if (model_.is_complex(inst)) {
      buffer_ += '(';
      for (Value record : model_.params(inst)) {
        buffer_ += model_.keyword(record.keyword_id());
        const Value list = model_.typed_child(record);
        params(model_.items(list));
      }
      buffer_ += ')';
    } else {
      buffer_ += model_.type_name(inst);
      params(model_.params(inst));
    }
    put(";\n");
  }

  const Model& model_;
  const TextSink& sink_;
  std::string buffer_;
};

}  // namespace

// Recursion here is bounded by Model::max_depth(), which the readers cap.
void append_value(const Model& model, Value v, std::string& out) {
  switch (v.kind()) {
    case ValueKind::Omitted:
      out += '$';
      return;
    case ValueKind::Derived:
      out += '*';
      return;
    case ValueKind::Integer:
    case ValueKind::Real:
      out += model.slice(v);
      return;
    case ValueKind::String:
      out += '\'';
      out += model.slice(v);
      out += '\'';
      return;
    case ValueKind::Enumeration:
      out += '.';
      out += model.slice(v);
      out += '.';
      return;
    case ValueKind::Binary:
      out += '"';
      out += model.slice(v);
      out += '"';
      return;
    case ValueKind::Reference:
      out += '#';
      out += std::to_string(v.id());
      return;
    case ValueKind::ConstantName:
      out += '#';
      out += model.slice(v);
      return;
    case ValueKind::ValueName:
      out += '@';
      out += model.slice(v);
      return;
    case ValueKind::Resource:
      out += '<';
      out += model.slice(v);
      out += '>';
      return;
    case ValueKind::List: {
      out += '(';
      bool first = true;
      for (Value item : model.items(v)) {
        if (!first) out += ',';
        first = false;
        append_value(model, item, out);
      }
      out += ')';
      return;
    }
    case ValueKind::Typed:
      out += model.keyword(v.keyword_id());
      out += '(';
      append_value(model, model.typed_child(v), out);
      out += ')';
      return;
  }
}

void write(const Model& model, const TextSink& sink) {
  Writer(model, sink).run();
}

std::string write_to_string(const Model& model) {
  std::string out;
  out.reserve(model.text().size() + 64);
  write(model, [&](std::string_view piece) { out += piece; });
  return out;
}

}  // namespace ncpost::p21
