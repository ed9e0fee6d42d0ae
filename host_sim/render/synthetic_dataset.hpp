#pragma once
// A small strobed dataset with its config, calibration and map (`irloc-sim synth`): a quick,
// schematic fixture for replay tests. Its pictures are flat bright discs and one lamp, not a
// model of a real ceiling; physically grounded datasets come from render_dataset().

#include <cstdint>
#include <filesystem>
#include <vector>

namespace irloc::sim {

struct SyntheticDatasetOptions {
  int width = 320;
  int height = 240;
  int frames = 20;                          // frames kept, LED on for even seq
  bool sixteen_bit = false;                 // 12-bit data in 16-bit PGMs
  std::vector<std::uint64_t> dropped_seqs;  // left out of the dataset, as a dropped frame is
};

// Writes DIR/frames.csv, the PGMs, DIR/config.yaml, DIR/calib.yaml and DIR/map.yaml.
// Throws io::InputError when DIR cannot be written.
void write_synthetic_dataset(const std::filesystem::path& dir, const SyntheticDatasetOptions& options);

}  // namespace irloc::sim
