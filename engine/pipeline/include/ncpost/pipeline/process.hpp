#pragma once
// Process-wide set-up that must happen once, on the main thread, before any job runs: libxml2's
// parser and libxslt's security and extension registrations (their globals are not safe to
// initialise from several threads at once).

#include <string_view>

namespace ncpost::pipeline {

void initialise_process();

}  // namespace ncpost::pipeline
