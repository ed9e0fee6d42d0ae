#pragma once
// Planning tools run before markers go on a ceiling: the ceiling brightness an LED ring gives a
// retro-reflector (the square-marker paper's ring design simulation) and the floor coverage of
// a landmark map (the LED-landmark paper's placement simulation).

#include <filesystem>
#include <string>

#include "host_sim/plots/plots.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Brightness, in % of the sensor's full scale, of retro-reflective material at each point of a
// square of the ceiling of half-size `half_extent` metres centred above the robot at its pose at
// t = 0; NaN where the camera does not see the ceiling. `cells` per side.
HeatMap led_ring_brightness(const Scenario& scenario, double half_extent, int cells);

// The most floor cells of a coverage or placement map (its work: cells x headings x landmarks).
inline constexpr int kMaxFloorCells = 250'000;

// For each floor cell (room.bounds, or the map's extent) the smallest number of landmarks in
// view over `headings` robot headings: LED landmarks that project into the image and whose
// emission cone reaches the camera, and dot and square markers seen whole. A floor of more than
// kMaxFloorCells cells is refused (io::InputError naming --cell) before any work.
HeatMap landmark_coverage(const Scenario& scenario, double cell, int headings);

// Share of the cells of a coverage map with at least k landmarks in view, in [0, 1].
double coverage_fraction(const HeatMap& coverage, int k);

}  // namespace irloc::sim
