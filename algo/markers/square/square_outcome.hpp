#pragma once
// Why a square marker pose attempt ended as it did: SourceResult::outcome holds the text (counted
// per source by irlocd --stats, docs/formats.md; the texts are docs/square_markers.md's).

#include <string_view>

namespace irloc::square {

enum class SquareOutcome {
  found,
  no_off_frame,     // the pair has no LED-off frame: no difference image (the source's; the detector never runs)
  bad_frames,       // the pair's frames differ in depth or are not of the calibrated size
  no_square,        // no four Hough peaks form a square of side d
  sides_too_thin,   // a side has too few tape points to refine
  side_hidden,      // a side is seen along less than min_visible_fraction of it
  solid_ambiguous,  // not exactly one side reads solid
  inconsistent,     // the refined square does not match the map (corner residual, side length)
  ambiguous,        // two hypotheses at different poses explain the tape about equally well
  unidentified,     // a square whose pattern no map square has, or one of several alike
                    // without a recent pose near one of them
};

// A string literal.
constexpr std::string_view to_string(SquareOutcome outcome) {
  switch (outcome) {
    case SquareOutcome::found: return "found";
    case SquareOutcome::no_off_frame: return "no LED-off frame";
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
