#pragma once
// Why a dot marker pose attempt ended as it did: SourceResult::outcome holds the text (counted per
// source by irlocd --stats, docs/formats.md).

#include <string_view>

namespace irloc::dot {

enum class DotOutcome {
  found,
  found_with_track_identified,  // the fit used a marker identified by the track (track_identification.hpp)
  no_off_frame,           // the pair has no LED-off frame: no difference image
  no_marker_decoded,      // no dot group decoded as a mapped marker
  pose_fit_failed,        // the decoded markers gave no pose
  low_confidence,         // the pose's confidence is below dot.confidence_floor
};

// A string literal.
constexpr std::string_view to_string(DotOutcome outcome) {
  switch (outcome) {
    case DotOutcome::found: return "found";
    case DotOutcome::found_with_track_identified: return "found, a marker identified by the track";
    case DotOutcome::no_off_frame: return "no LED-off frame";
    case DotOutcome::no_marker_decoded: return "no mapped marker decoded";
    case DotOutcome::pose_fit_failed: return "pose fit failed";
    case DotOutcome::low_confidence: return "confidence below the floor";
  }
  return "?";
}

}  // namespace irloc::dot
