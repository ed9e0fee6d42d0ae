#pragma once
// Why an outside-in pose attempt ended as it did: SourceResult::outcome holds the text (counted per
// source by irlocd --stats, docs/formats.md; the texts are docs/outside_in.md's).

#include <string_view>

namespace irloc::outside_in {

enum class OutsideInOutcome {
  found,
  unsupported_depth,    // a 16-bit frame: the source works on 8-bit frames (YUYV luma, grey)
  learning_background,  // the first frame: it only starts the background
  no_robot,             // no blob the box explains, and no live track
  occluded,             // a live track without a fit this frame (it coasts)
  heading_unknown,      // a new track that has not moved far enough to tell its heading
  heading_uncertain,    // the heading's sigma, filter and floor reference together, is over 5 degrees
  not_explained,        // the track's blob is not the box alone (a ghost merged, a face missed): no pose
};

// A string literal.
constexpr std::string_view to_string(OutsideInOutcome outcome) {
  switch (outcome) {
    case OutsideInOutcome::found: return "found";
    case OutsideInOutcome::unsupported_depth: return "unsupported_depth";
    case OutsideInOutcome::learning_background: return "learning_background";
    case OutsideInOutcome::no_robot: return "no_robot";
    case OutsideInOutcome::occluded: return "occluded";
    case OutsideInOutcome::heading_unknown: return "heading_unknown";
    case OutsideInOutcome::heading_uncertain: return "heading_uncertain";
    case OutsideInOutcome::not_explained: return "not_explained";
  }
  return "?";
}

}  // namespace irloc::outside_in
