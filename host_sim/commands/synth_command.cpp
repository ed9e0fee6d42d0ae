// irloc-sim synth: a small schematic strobed dataset with its config, calibration and map.

#include <cstdio>
#include <memory>
#include <string>

#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/render/synthetic_dataset.hpp"

namespace irloc::sim {

void add_synth_command(CommandLine& command_line) {
  struct Options {
    std::string out;
    SyntheticDatasetOptions dataset;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("synth", "write a small schematic strobed dataset with config, calibration and map");
  command.text("--out", options->out, "dataset folder to write", Need::required);
  command.integer("--frames", options->dataset.frames, "number of frames", 1, 100000);
  command.integer("--width", options->dataset.width, "frame width", 16, 8192);
  command.integer("--height", options->dataset.height, "frame height", 16, 8192);
  command.flag("--sixteen-bit", options->dataset.sixteen_bit, "12-bit data in 16-bit PGMs");
  command.integers("--drop", options->dataset.dropped_seqs, "sequence numbers to leave out, as dropped frames");
  command.action([options] {
    io::RunFiles files;
    files.new_folder("--out", options->out);
    files.check();
    write_synthetic_dataset(options->out, options->dataset);
    std::printf("irloc-sim: wrote the synthetic dataset to %s\n", options->out.c_str());
  });
}

}  // namespace irloc::sim
