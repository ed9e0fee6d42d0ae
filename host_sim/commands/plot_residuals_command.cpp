// irloc-sim plot-residuals: a picture of the dot residuals before and after irlocd --calibrate,
// written into its OUT_DIR.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "io/config/calibration_file.hpp"
#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/plots/calibration_residuals.hpp"
#include "host_sim/plots/plots.hpp"

namespace irloc::sim {

void add_plot_residuals_command(CommandLine& command_line) {
  auto calibrated = std::make_shared<std::string>();
  Subcommand command = command_line.add("plot-residuals", "picture of the dot residuals before/after irlocd --calibrate OUT_DIR");
  command.text("--calibration", *calibrated, "the OUT_DIR of irlocd --calibrate", Need::required);
  command.action([calibrated] {
    const std::filesystem::path dir(*calibrated);
    io::RunFiles files;
    files.inputs({dir / "calib.yaml", dir / "residuals.csv"});
    files.output_file("--calibration", dir / "residuals.png");
    files.check();
    const CameraIntrinsics camera = io::load_camera_info(dir / "calib.yaml");
    plot_calibration_residuals(dir / "residuals.png", read_calibration_residuals(dir / "residuals.csv"), camera.width,
                               camera.height);
    std::printf("irloc-sim: residual picture in %s\n", (dir / "residuals.png").c_str());
  });
}

}  // namespace irloc::sim
