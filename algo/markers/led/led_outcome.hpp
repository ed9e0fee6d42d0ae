#pragma once
// Why an LED pose attempt ended as it did: SourceResult::outcome holds the text (counted per
// source by irlocd --stats, docs/formats.md).

#include <string_view>

namespace irloc::led {

enum class LedOutcome {
  found,
  too_few_leds,             // fewer detections than the dof needs
  no_association,           // no minimal-set hypothesis explains enough detections
  no_hypothesis_verified,   // hypotheses were found, none passed refinement and acceptance
  ambiguous,                // two different poses explain the image about equally well
  unconfirmed,              // the search's pose matches no LED beyond a minimal set, which any detections fit
  search_budget_exhausted,  // max_hypotheses solver calls were not enough
  track_lost,               // tracking: the predicted LEDs did not verify (the search follows)
  track_jumped,             // tracking: the pose left the prediction (the search follows)
  out_of_reach,             // the searched pose is further from the last pose than the robot can move
  too_uncertain,            // the fit's position standard deviation is above max_position_sigma
};

// A string literal.
constexpr std::string_view to_string(LedOutcome outcome) {
  switch (outcome) {
    case LedOutcome::found: return "found";
    case LedOutcome::too_few_leds: return "too few LEDs";
    case LedOutcome::no_association: return "no association";
    case LedOutcome::no_hypothesis_verified: return "no hypothesis verified";
    case LedOutcome::ambiguous: return "ambiguous";
    case LedOutcome::unconfirmed: return "unconfirmed";
    case LedOutcome::search_budget_exhausted: return "search budget exhausted";
    case LedOutcome::track_lost: return "track lost";
    case LedOutcome::track_jumped: return "track jumped";
    case LedOutcome::out_of_reach: return "out of reach";
    case LedOutcome::too_uncertain: return "too uncertain";
  }
  return "?";
}

}  // namespace irloc::led
