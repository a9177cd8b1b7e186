// Test helper for ProfileStoreCrash: puts two versions of profile "crash" into DIR, alternately,
// until it is killed. Usage: profile_store_writer DIR. It writes one byte to stdout when it is
// about to start writing, so that the test's kills land in the writes and not in the start-up
// (which under a sanitizer on a loaded machine took longer than all the test's delays).
#include <cstdio>

#include "ncpost/profile/profile.hpp"
#include "store_fixture.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: profile_store_writer DIR\n");
    return 2;
  }
  ncpost::xslt::initialise();
  using namespace ncpost::profile;
  ProfileStore store(argv[1], StoreOptions{.writable = true, .fallback = builtin_directory()});
  const std::string json[2] = {test_store::profile_json("crash", "Version A"),
                               test_store::profile_json("crash", "Version B")};
  const std::string xsl[2] = {test_store::stylesheet("A"), test_store::stylesheet("B")};
  std::fputc('w', stdout);
  std::fflush(stdout);
  for (unsigned i = 0;; ++i) {
    const auto r = store.put("crash", json[i % 2], xsl[i % 2]);
    if (!r.profile) {
      for (const auto& d : r.diagnostics)
        std::fprintf(stderr, "%s\n", ncpost::diag::format(d).c_str());
      return 1;
    }
  }
}
