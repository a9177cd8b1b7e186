#include "ncpost/pipeline/process.hpp"

#include "ncpost/p28/p28.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::pipeline {

void initialise_process() {
  p28::initialise_xml();
  xslt::initialise();
}

}  // namespace ncpost::pipeline
