#pragma once
// A small strobed dataset with its config, calibration and map: the fixture of the replay
// tests and of `make demo` until the physically grounded renderer exists. Its pictures are
// schematic (flat bright discs, one lamp), not a model of a real ceiling.

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
// Throws hal::InputError when DIR cannot be written.
void write_synthetic_dataset(const std::filesystem::path& dir, const SyntheticDatasetOptions& options);

}  // namespace irloc::sim
