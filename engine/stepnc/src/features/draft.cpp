#include "draft.hpp"

namespace ncpost::stepnc::features {

Path Draft::finish(bool ok) && {
  Path path;
  path.ok = ok;
  if (ok) path.moves = std::move(moves_);
  return path;
}

}  // namespace ncpost::stepnc::features
