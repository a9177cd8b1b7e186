#pragma once
// Shared by the store tests and their writer helper: two versions of one uploaded profile,
// made from the built-in linuxcnc profile with another id and name.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "corpus.hpp"

namespace ncpost::profile::test_store {

inline std::string profile_json(const std::string& id, const std::string& name) {
  auto doc = nlohmann::json::parse(
      ncpost::test::read_file(ncpost::test::source_dir() / "stylesheets/linuxcnc/profile.json"));
  doc["id"] = id;
  doc["name"] = name;
  doc.erase("$schema");
  return doc.dump(2);
}

// The linuxcnc stylesheet with a marker comment, so that versions differ in both files.
inline std::string stylesheet(const std::string& marker) {
  std::string xsl =
      ncpost::test::read_file(ncpost::test::source_dir() / "stylesheets/linuxcnc/post.xsl");
  return xsl + "<!-- " + marker + " -->\n";
}

// The built-in linuxcnc dialect under another id.
inline std::string dialect_json(const std::string& id) {
  auto doc = nlohmann::json::parse(
      ncpost::test::read_file(ncpost::test::source_dir() / "stylesheets/linuxcnc/dialect.json"));
  doc["id"] = id;
  doc.erase("$schema");
  return doc.dump(1);
}

}  // namespace ncpost::profile::test_store
