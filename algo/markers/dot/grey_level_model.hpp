#pragma once
// The paper's grey-level model of dot intensities: a two-component Gaussian mixture over a dot
// blob's mean strobe difference (grey levels), one component for genuine retro-reflective dots,
// one for clutter. The posterior of the dot component is a dot's grey-level evidence.

#include <span>

#include "algo/markers/dot/dot_source_config.hpp"

namespace irloc::dot {

// P(dot | intensity) in [0, 1]. Allocates nothing.
double dot_posterior(const GreyLevelModel& model, double intensity);

// Fits the mixture to sample intensities by expectation-maximisation, starting from `start`
// (the component called dot is kept as the brighter one). For the fitting tool, not the
// per-frame path. Returns start unchanged for fewer than 4 samples.
GreyLevelModel fit_grey_level_model(std::span<const double> intensities, const GreyLevelModel& start,
                                    int iterations = 200);

}  // namespace irloc::dot
