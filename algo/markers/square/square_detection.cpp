#include "algo/markers/square/square_detection.hpp"

namespace irloc::square {

std::string_view to_string(SquareOutcome outcome) {
  switch (outcome) {
    case SquareOutcome::found: return "found";
    case SquareOutcome::bad_frames: return "bad_frames";
    case SquareOutcome::no_square: return "no_square";
    case SquareOutcome::sides_too_thin: return "sides_too_thin";
    case SquareOutcome::side_hidden: return "side_hidden";
    case SquareOutcome::solid_ambiguous: return "solid_ambiguous";
    case SquareOutcome::inconsistent: return "inconsistent";
    case SquareOutcome::ambiguous: return "ambiguous";
    case SquareOutcome::unidentified: return "unidentified";
  }
  return "?";
}

}  // namespace irloc::square
