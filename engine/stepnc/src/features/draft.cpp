#include "draft.hpp"

namespace ncpost::stepnc::features {

void Draft::arc(Vec3 to, Vec3 centre, int turns) {
  Move move{Move::Kind::Arc, to, centre};
  move.turns = turns;
  add(move);
}

Path Draft::finish(bool ok) && {
  Path path;
  path.ok = ok;
  if (ok) path.moves = std::move(moves_);
  return path;
}

}  // namespace ncpost::stepnc::features
