#include "draft.hpp"

namespace ncpost::stepnc::features {

void Draft::place_from(std::size_t first, const detail::Frame& frame) {
  for (std::size_t k = first; k < moves_.size(); ++k) {
    Move& m = moves_[k];
    switch (m.kind) {
      case Move::Kind::Rapid:
      case Move::Kind::Feed:
      case Move::Kind::Cycle:
        m.to = frame.point(m.to);
        break;
      case Move::Kind::Arc:
        m.to = frame.point(m.to);
        m.centre = frame.point(m.centre);
        break;
      case Move::Kind::FeedRate:
      case Move::Kind::Spindle:
      case Move::Kind::Dwell:
        break;
    }
  }
}

Path Draft::finish(bool ok) && {
  Path path;
  path.ok = ok;
  if (ok) path.moves = std::move(moves_);
  return path;
}

}  // namespace ncpost::stepnc::features
