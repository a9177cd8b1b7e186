#include <iostream>

#include "cli_support.hpp"

namespace ncpost::cli {

// Placeholder until engine/express lands (issue 3); says so instead of pretending.
int run_schema(Args /*args*/) {
  std::cerr << "ncpost: error: NCPOST-001: 'ncpost schema' is not implemented yet (issue 3)\n";
  return kExitUsage;
}

}  // namespace ncpost::cli
