#pragma once
// The curve reader moved to the public headers (shared with engine/ap238); this name stays so
// that the feature generator's includes need not change.
#include "ncpost/stepnc/curves.hpp"
