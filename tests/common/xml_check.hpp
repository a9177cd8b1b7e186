#pragma once
// Whether a string is well-formed XML, for tests of the stages that write XML (link libxml2).

#include <libxml/parser.h>

#include <string>

namespace ncpost::test {

inline bool well_formed(const std::string& xml) {
  xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), nullptr, nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  const bool ok = doc != nullptr;
  xmlFreeDoc(doc);
  return ok;
}

}  // namespace ncpost::test
