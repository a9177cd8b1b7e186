// Makes a large, realistic STEP-NC file for benchmarks: the workingsteps and explicit toolpaths
// of NIST's ex1E.stp, replicated with renumbered ids until the file reaches a requested size.
// Every copy is a full set of instances (workingsteps, operations, toolpaths, tools) whose ids
// are shifted by a multiple of the source's largest id; the main workplan lists the workingsteps
// of all copies in order, so interpreting the result machines the part many times over.
//
//   make_large_stepnc SOURCE.stp SIZE_MB OUT.stp

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"

namespace {

using ncpost::p21::Instance;
using ncpost::p21::Model;
using ncpost::p21::Value;
using ncpost::p21::ValueKind;

// Writes a value with every reference shifted by `shift`; recursion is bounded by the
// reader's list-depth limit.
void append_shifted(const Model& m, Value v, std::uint64_t shift, std::string& out) {
  if (v.is_reference()) {
    out += '#';
    out += std::to_string(v.id() + shift);
  } else if (v.is_list()) {
    out += '(';
    bool first = true;
    for (Value item : m.items(v)) {
      if (!first) out += ',';
      first = false;
      append_shifted(m, item, shift, out);
    }
    out += ')';
  } else if (v.kind() == ValueKind::Typed) {
    out += m.keyword(v.keyword_id());
    out += '(';
    append_shifted(m, m.typed_child(v), shift, out);
    out += ')';
  } else {
    ncpost::p21::append_value(m, v, out);
  }
}

void append_instance(const Model& m, const Instance& inst, std::uint64_t shift, std::string& out) {
  out += '#';
  out += std::to_string(inst.id + shift);
  out += '=';
  if (inst.keyword == Model::kComplexKeyword) {
    // (A(..)B(..)): each partial record is a typed value whose child is its parameter list.
    out += '(';
    for (Value record : m.params(inst)) {
      out += m.keyword(record.keyword_id());
      append_shifted(m, m.typed_child(record), shift, out);
    }
    out += ");\n";
    return;
  }
  out += m.type_name(inst);
  out += '(';
  bool first = true;
  for (Value v : m.params(inst)) {
    if (!first) out += ',';
    first = false;
    append_shifted(m, v, shift, out);
  }
  out += ");\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: make_large_stepnc SOURCE.stp SIZE_MB OUT.stp\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  auto read = ncpost::p21::read(text.str());
  if (!read.ok()) {
    std::cerr << "source has errors\n";
    return 1;
  }
  const Model& m = read.model;
  const auto projects = m.instances_of("PROJECT");
  if (projects.size() != 1) {
    std::cerr << "source needs exactly one PROJECT\n";
    return 1;
  }
  const Instance& project = *projects[0];
  const Instance* main = m.find(m.params(project)[1].id());
  const Value elements = m.params(*main)[1];
  const double target = std::stod(argv[2]) * 1024 * 1024;

  std::uint64_t max_id = 0;
  for (const auto& inst : m.instances()) max_id = std::max(max_id, inst.id);
  // Ids stay dense, as real writers make them: copy c shifts every id by c * (max_id + 1).
  const std::uint64_t stride = max_id + 1;

  std::size_t per_copy = 0;
  {
    std::string probe;
    // Measured with a large shift, so that longer ids are counted.
    const std::uint64_t typical_shift = stride * 1000;
    for (const auto& inst : m.instances())
      if (&inst != &project && &inst != main) append_instance(m, inst, typical_shift, probe);
    per_copy = probe.size() + m.items(elements).size() * 9;  // plus the workplan's references
  }
  const auto copies = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(target / static_cast<double>(per_copy)));

  std::ofstream out(argv[3], std::ios::binary);
  out << "ISO-10303-21;\nHEADER;\n"
         "FILE_DESCRIPTION(('ncpost benchmark input: NIST ex1E replicated "
      << copies
      << " times'),'2;1');\n"
         "FILE_NAME('large.stp','2026-11-21T00:00:00',('ncpost "
         "bench'),(''),'','make_large_stepnc','');\n"
         "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\nENDSEC;\nDATA;\n";
  std::string buffer;
  append_instance(m, project, 0, buffer);
  // The main workplan lists every copy's workingsteps, copy by copy.
  buffer += '#' + std::to_string(main->id) + "=WORKPLAN(";
  ncpost::p21::append_value(m, m.params(*main)[0], buffer);
  buffer += ",(";
  for (std::uint64_t c = 0; c < copies; ++c) {
    bool first = c == 0;
    for (Value e : m.items(elements)) {
      if (!first) buffer += ',';
      first = false;
      buffer += '#' + std::to_string(e.id() + c * stride);
    }
    if (buffer.size() > (1 << 20)) {
      out << buffer;
      buffer.clear();
    }
  }
  buffer += ')';
  for (std::size_t i = 2; i < m.params(*main).size(); ++i) {
    buffer += ',';
    ncpost::p21::append_value(m, m.params(*main)[i], buffer);
  }
  buffer += ");\n";
  for (std::uint64_t c = 0; c < copies; ++c) {
    for (const auto& inst : m.instances())
      if (&inst != &project && &inst != main) append_instance(m, inst, c * stride, buffer);
    if (buffer.size() > (1 << 20)) {
      out << buffer;
      buffer.clear();
    }
  }
  out << buffer << "ENDSEC;\nEND-ISO-10303-21;\n";
  std::cerr << "wrote " << copies << " copies of " << m.instances().size() << " instances to "
            << argv[3] << '\n';
  return 0;
}
