// libFuzzer target for the ISO 10303-28 XML reader (engine/p28): any bytes must give a model
// and diagnostics, never a crash, a hang or a sanitizer report, read without a schema and with
// the built-in ISO 14649 schema. Untrusted XML must never reach a file or the network: the
// harness replaces libxml2's external entity loader and puts an input callback in front of
// libxml2's own (file, HTTP, FTP), both of which trap if the reader ever asks for anything, and
// the model text and diagnostics must never hold the first line of /etc/passwd (the seeds have
// external entities and DTDs that name it). A clean read must write back as P21 and read again
// to an equal model.

#include <libxml/parser.h>
#include <libxml/xmlIO.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "ncpost/express/registry.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"
#include "ncpost/p28/p28.hpp"

namespace {

xmlParserInputPtr trap_entity(const char*, const char*, xmlParserCtxtPtr) {
  __builtin_trap();
}
int trap_match(const char*) {
  __builtin_trap();
}
void* never_open(const char*) {
  return nullptr;
}
int never_read(void*, char*, int) {
  return -1;
}
int never_close(void*) {
  return 0;
}

bool set_up() {
  ncpost::p28::initialise_xml();
  xmlSetExternalEntityLoader(trap_entity);
  // Input callbacks are tried newest first: this one sees every URI libxml2 would open.
  if (xmlRegisterInputCallbacks(trap_match, never_open, never_read, never_close) < 0)
    __builtin_trap();
  return true;
}

constexpr std::string_view kSecret = "root:x:0:0:";

// Whether the secret came out of a document that does not hold it itself.
bool leaks(std::string_view xml, const ncpost::p21::ReadResult& r) {
  if (xml.find(kSecret) != std::string_view::npos) return false;
  if (r.model.text().find(kSecret) != std::string_view::npos) return true;
  for (const auto& d : r.diagnostics)
    if (d.message.find(kSecret) != std::string::npos) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool ready = set_up();
  (void)ready;
  const std::string_view xml(reinterpret_cast<const char*>(data), size);
  ncpost::p28::ReadOptions options;
  options.max_errors = 100;
  const auto plain = ncpost::p28::read(xml, nullptr, options);
  if (leaks(xml, plain)) __builtin_trap();
  const auto schema = ncpost::express::builtin_schema();
  const auto typed = ncpost::p28::read(xml, &schema->schemas, options);
  if (leaks(xml, typed)) __builtin_trap();
  if (typed.ok()) {
    const auto back = ncpost::p21::read(ncpost::p21::write_to_string(typed.model));
    if (!back.ok() || ncpost::p21::first_difference(typed.model, back.model)) __builtin_trap();
  }
  return 0;
}
