#pragma once
// Renders a scenario to a frame dataset (docs/formats.md): the strobed frames, truth.csv, and the
// config, calibration and map irlocd needs to replay it.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "algo/geometry/pose.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// One frame of a rendered dataset and the robot's true pose T_W_B at its exposure.
struct TruthRow {
  std::uint64_t seq = 0;
  std::int64_t t_ns = 0;
  bool led_on = false;
  double x = 0, y = 0, z = 0, roll = 0, pitch = 0, yaw = 0;
};

// Writes truth.csv (docs/formats.md); throws io::InputError when it cannot.
void write_truth_csv(const std::filesystem::path& path, const std::vector<TruthRow>& rows);

// Capture time of frame `seq`: 1 s plus seq frame periods, in nanoseconds.
std::int64_t frame_time_ns(const Scenario& scenario, std::uint64_t seq);

// Sequence numbers the scenario drops (listed, and drawn with drop_probability from the seed).
bool is_dropped(const Scenario& scenario, std::uint64_t seq);

// Called after each frame with (frames done, frames in the scenario).
using Progress = std::function<void(int, int)>;

// Writes DIR/frames.csv, DIR/frame_*.pgm, DIR/truth.csv, DIR/config.yaml, DIR/calib.yaml and
// DIR/map.yaml. Returns the truth of every written frame. Throws io::InputError when DIR cannot
// be written or the scenario has no map.
std::vector<TruthRow> render_dataset(const Scenario& scenario, const std::filesystem::path& dir,
                                     const Progress& progress = {});

}  // namespace irloc::sim
