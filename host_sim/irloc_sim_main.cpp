// irloc-sim: the host simulator. For now it writes the small synthetic dataset that the replay
// tests and `make demo` use.

#include <cstdio>

#include <CLI/CLI.hpp>

#include "hal/input_error.hpp"
#include "host_sim/synthetic_dataset.hpp"

int main(int argc, char** argv) {
  CLI::App app{"irloc-sim: host simulator"};
  app.require_subcommand(1);

  std::string out;
  irloc::sim::SyntheticDatasetOptions options;
  CLI::App* synth = app.add_subcommand("synth", "write a small schematic strobed dataset with config, calibration and map");
  synth->add_option("--out", out, "dataset folder to write")->required();
  synth->add_option("--frames", options.frames, "number of frames")->check(CLI::Range(1, 100000));
  synth->add_option("--width", options.width, "frame width")->check(CLI::Range(16, 8192));
  synth->add_option("--height", options.height, "frame height")->check(CLI::Range(16, 8192));
  synth->add_flag("--sixteen-bit", options.sixteen_bit, "12-bit data in 16-bit PGMs");
  synth->add_option("--drop", options.dropped_seqs, "sequence numbers to leave out, as dropped frames");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  }
  try {
    irloc::sim::write_synthetic_dataset(out, options);
    std::printf("irloc-sim: wrote the synthetic dataset to %s\n", out.c_str());
    return 0;
  } catch (const irloc::hal::InputError& e) {
    std::fprintf(stderr, "irloc-sim: error: %s\n", e.what());
    return 1;
  }
}
