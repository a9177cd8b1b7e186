#pragma once
// Whether a string is well-formed XML, for tests of the stages that write XML (link libxml2).

#include <libxml/parser.h>
#include <libxml/relaxng.h>

#include <string>

namespace ncpost::test {

inline bool well_formed(const std::string& xml) {
  xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), nullptr, nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  const bool ok = doc != nullptr;
  xmlFreeDoc(doc);
  return ok;
}

// Empty when `xml` is well-formed and valid against the RELAX NG grammar at `rng` (which may
// include others by relative path); otherwise what went wrong.
inline std::string rng_errors(const std::string& xml, const std::string& rng) {
  std::string errors;
  xmlRelaxNGParserCtxtPtr parser = xmlRelaxNGNewParserCtxt(rng.c_str());
  xmlRelaxNGPtr schema = parser != nullptr ? xmlRelaxNGParse(parser) : nullptr;
  xmlRelaxNGFreeParserCtxt(parser);
  if (schema == nullptr) return "the grammar does not load: " + rng;
  xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), nullptr, nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  if (doc == nullptr) {
    errors = "not well-formed";
  } else {
    xmlRelaxNGValidCtxtPtr validator = xmlRelaxNGNewValidCtxt(schema);
    xmlRelaxNGSetValidStructuredErrors(
        validator,
        [](void* user, xmlErrorPtr error) {
          if (error != nullptr && error->message != nullptr)
            *static_cast<std::string*>(user) += error->message;
        },
        &errors);
    const int rc = xmlRelaxNGValidateDoc(validator, doc);
    if (rc != 0 && errors.empty()) errors = "invalid (rc " + std::to_string(rc) + ")";
    xmlRelaxNGFreeValidCtxt(validator);
    xmlFreeDoc(doc);
  }
  xmlRelaxNGFree(schema);
  return errors;
}

}  // namespace ncpost::test
