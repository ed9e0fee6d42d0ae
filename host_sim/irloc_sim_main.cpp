// irloc-sim: the host simulator. Renders physically grounded IR scenes from scenario files,
// replays them through irlocd, and measures the result against ground truth
// (docs/simulator.md).

#include <cmath>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include <CLI/CLI.hpp>

#include "algo/geometry/pose.hpp"
#include "hal/config/calibration_file.hpp"
#include "hal/config/config_file.hpp"
#include "hal/config/map_file.hpp"
#include "hal/files/run_files.hpp"
#include "hal/input_error.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/default_scenario.hpp"
#include "host_sim/tools/dot_tools.hpp"
#include "host_sim/tools/led_placement.hpp"
#include "host_sim/tools/planning.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
#include "host_sim/run/simulation_run.hpp"
#include "host_sim/tools/survey_check.hpp"
#include "host_sim/render/synthetic_dataset.hpp"

namespace {

using namespace irloc::sim;

// The scenario file, or the embedded default when none is given; --frames overrides its count.
Scenario scenario_from(const std::string& path, int frames) {
  Scenario scenario = path.empty() ? parse_scenario(std::string(default_scenario_yaml()), "<default scenario>")
                                   : load_scenario(path);
  if (frames > 0) scenario.frames = frames;
  return scenario;
}

// A progress bar on stderr when it is a terminal; nothing otherwise (logs stay clean).
Progress progress_bar(const char* what) {
  if (isatty(STDERR_FILENO) == 0) return {};
  return [what](int done, int total) {
    constexpr int kWidth = 40;
    const int filled = done * kWidth / total;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d", what, filled, "########################################",
                 kWidth - filled, "", done, total);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

// A number option's documented range (docs/simulator.md): finite and within [low, high], checked
// before any work; CLI11 names the option in its message.
CLI::Validator finite_range(double low, double high) {
  char description[64];
  std::snprintf(description, sizeof description, "FLOAT in [%g, %g]", low, high);
  return CLI::Validator(
      [low, high](const std::string& text) -> std::string {
        double value = 0;
        try {
          std::size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return "not a number: " + text;
        } catch (const std::exception&) {
          return "not a number: " + text;
        }
        if (std::isfinite(value) && value >= low && value <= high) return {};
        char message[120];
        std::snprintf(message, sizeof message, "must be a finite number in [%g, %g], got %s", low, high, text.c_str());
        return message;
      },
      description);
}

// Every file in a dataset folder: what a replay of it reads.
std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dataset) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(dataset, error)) {
    files.push_back(entry.path());
  }
  return files;
}

// A replay config's own files: the config, its calibration and its map.
std::vector<std::filesystem::path> config_files(const std::filesystem::path& config) {
  const irloc::hal::RobotConfig robot = irloc::hal::load_robot_config(config);
  std::vector<std::filesystem::path> files = {config, robot.calibration_file};
  if (!robot.map_file.empty()) files.push_back(robot.map_file);
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"irloc-sim: host simulator (docs/simulator.md)"};
  app.require_subcommand(1);

  // An empty file name is a mistake (an unset shell variable), never "the default" or "".
  const CLI::Validator non_empty([](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); },
                                 "NOT EMPTY");
  std::string out;
  std::string scenario_path;
  int frames = 0;

  SyntheticDatasetOptions synth_options;
  CLI::App* synth = app.add_subcommand("synth", "write a small schematic strobed dataset with config, calibration and map");
  synth->add_option("--out", out, "dataset folder to write")->required()->check(non_empty);
  synth->add_option("--frames", synth_options.frames, "number of frames")->check(CLI::Range(1, 100000));
  synth->add_option("--width", synth_options.width, "frame width")->check(CLI::Range(16, 8192));
  synth->add_option("--height", synth_options.height, "frame height")->check(CLI::Range(16, 8192));
  synth->add_flag("--sixteen-bit", synth_options.sixteen_bit, "12-bit data in 16-bit PGMs");
  synth->add_option("--drop", synth_options.dropped_seqs, "sequence numbers to leave out, as dropped frames");

  CLI::App* render = app.add_subcommand("render", "render a scenario to a dataset irlocd can replay");
  render->add_option("--scenario", scenario_path, "scenario YAML (default: the embedded default scenario)")->check(non_empty);
  render->add_option("--out", out, "dataset folder to write")->required()->check(non_empty);
  render->add_option("--frames", frames, "override the scenario's frame count")->check(CLI::Range(1, 1000000));

  CLI::App* run = app.add_subcommand("run", "render a scenario, replay it through irlocd, write metrics and plots");
  run->add_option("--scenario", scenario_path, "scenario YAML (default: the embedded default scenario)")->check(non_empty);
  run->add_option("--out", out, "output folder")->default_val("irloc-sim-run")->check(non_empty);
  run->add_option("--frames", frames, "override the scenario's frame count")->check(CLI::Range(1, 1000000));

  double half_extent = 2.5;
  int cells = 120;
  CLI::App* ledmap = app.add_subcommand("ledmap", "heat map of the ceiling brightness an LED ring gives a retro-reflector");
  ledmap->add_option("--scenario", scenario_path, "scenario YAML (its led_ring, camera and pose at t = 0)")->required()->check(non_empty);
  ledmap->add_option("--out", out, "PNG to write")->required()->check(non_empty);
  ledmap->add_option("--half-extent", half_extent, "half size of the ceiling square, metres")->check(finite_range(0.1, 100));
  ledmap->add_option("--cells", cells, "cells per side")->check(CLI::Range(8, 1000));
  double scale_max = 0;
  ledmap->add_option("--scale-max", scale_max, "top of the colour scale, % of full scale (default: the peak)")
      ->check(finite_range(0.01, 10000));

  int k = 3;
  double cell = 0.1;
  int headings = 36;
  CLI::App* coverage = app.add_subcommand("coverage", "floor map of how many landmarks are in view at every heading");
  coverage->add_option("--scenario", scenario_path, "scenario YAML (its map, camera and room)")->required()->check(non_empty);
  coverage->add_option("--out", out, "PNG to write")->required()->check(non_empty);
  coverage->add_option("--k", k, "landmarks needed in view")->check(CLI::Range(1, 100));
  coverage->add_option("--cell", cell, "floor cell size, metres")->check(finite_range(0.001, 100));
  coverage->add_option("--headings", headings, "headings tried per cell")->check(CLI::Range(1, 720));

  double pixel_sigma = 0.17;
  double scale_mm = 0;
  CLI::App* ledplan = app.add_subcommand("ledplan", "floor map of the LED source's expected position error at the worst heading");
  ledplan->add_option("--scenario", scenario_path, "scenario YAML (its LED landmarks, camera, room and robot.dof)")->required()->check(non_empty);
  ledplan->add_option("--out", out, "PNG to write")->required()->check(non_empty);
  ledplan->add_option("--cell", cell, "floor cell size, metres")->check(finite_range(0.001, 100));
  ledplan->add_option("--headings", headings, "headings tried per cell")->check(CLI::Range(1, 720));
  ledplan->add_option("--pixel-sigma", pixel_sigma, "LED centre noise, pixels (the paper's: 0.17)")->check(finite_range(0.001, 100));
  ledplan->add_option("--scale-max", scale_mm, "top of the colour scale, mm (default: the largest error)")
      ->check(finite_range(0.001, 1e6));

  app.add_subcommand("default-scenario", "print the embedded default scenario YAML");

  std::string config_path, dataset_path, mount_out;
  CLI::App* fit_confidence = app.add_subcommand("fit-confidence", "fit the dot path's grey-level model to a dataset");
  fit_confidence->add_option("--config", config_path, "config YAML")->required()->check(non_empty);
  fit_confidence->add_option("--dataset", dataset_path, "dataset folder")->required()->check(non_empty);
  CLI::App* calibrate_mount = app.add_subcommand("calibrate-mount", "camera offset from a spin-in-place dataset");
  calibrate_mount->add_option("--config", config_path, "config YAML")->required()->check(non_empty);
  calibrate_mount->add_option("--dataset", dataset_path, "spin-in-place dataset folder")->required()->check(non_empty);
  calibrate_mount->add_option("--out", mount_out, "config to write (never --config itself, nor another input)")
      ->required()
      ->check(non_empty);

  std::string calibrated_dir;
  CLI::App* plot_residuals =
      app.add_subcommand("plot-residuals", "picture of the dot residuals before/after irlocd --calibrate OUT_DIR");
  plot_residuals->add_option("--calibration", calibrated_dir, "the OUT_DIR of irlocd --calibrate")->required()->check(non_empty);
  std::string drawing_path, estimate_path, truth_path;
  CLI::App* survey_map = app.add_subcommand(
      "survey-map", "a surveyed map against the truth (errors), or against the map it started from (moves): a top-view picture");
  survey_map->add_option("--drawing", drawing_path, "the map the survey started from")->required()->check(non_empty);
  survey_map->add_option("--estimate", estimate_path, "the map irlocd --survey wrote")->required()->check(non_empty);
  survey_map->add_option("--truth", truth_path, "the true map (a rendered dataset's map.yaml); without it (a real run), the moves")->check(non_empty);
  survey_map->add_option("--out", out, "PNG to write")->required()->check(non_empty);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  }
  try {
    // Every output is checked against the one output policy before any work (docs/formats.md,
    // "Output files").
    irloc::hal::RunFiles files;
    if (!scenario_path.empty()) files.input(scenario_path);
    if (synth->parsed()) {
      files.new_folder("--out", out);
      files.check();
      write_synthetic_dataset(out, synth_options);
      std::printf("irloc-sim: wrote the synthetic dataset to %s\n", out.c_str());
    } else if (render->parsed()) {
      const Scenario scenario = scenario_from(scenario_path, frames);
      files.inputs(referenced_files(scenario));
      std::size_t rendered = 0;
      if (scenario.outside_in) {
        // Several wall cameras: one dataset each, OUT/camera_<i>.
        std::vector<std::filesystem::path> dirs;
        for (std::size_t i = 0; i < scenario.outside_in->cameras.size(); ++i) {
          dirs.push_back(scenario.outside_in->cameras.size() == 1 ? std::filesystem::path(out)
                                                                 : std::filesystem::path(out) / ("camera_" + std::to_string(i)));
          files.new_folder("--out", dirs.back());
        }
        files.check();
        rendered = render_outside_in_datasets(scenario, dirs, progress_bar("rendering")).front().size();
      } else {
        files.new_folder("--out", out);
        files.check();
        rendered = render_dataset(scenario, out, progress_bar("rendering")).size();
      }
      std::printf("irloc-sim: rendered %zu frames of %s to %s\n", rendered, scenario.name.c_str(), out.c_str());
    } else if (run->parsed()) {
      const Scenario scenario = scenario_from(scenario_path, frames);
      files.inputs(referenced_files(scenario));
      files.output_folder("--out", out, kRunOutputFiles);
      for (const std::filesystem::path& dataset : run_dataset_folders(scenario, out)) files.replaced_folder("--out", dataset);
      files.check();
      const RunOutputs outputs = run_scenario(scenario, out, progress_bar("rendering"));
      // irlocd's summary line (one per wall camera); its stage times are in the metrics below.
      std::printf("irloc-sim run: %s\n  rendered in %.1f s; %s\n%s", scenario.name.c_str(), outputs.render_seconds,
                  outputs.irlocd_log.c_str(), summarize(outputs.metrics).c_str());
      for (std::size_t i = 0; i < outputs.cameras.size(); ++i) {
        std::printf("  camera %zu (component id %d):\n%s", i, outputs.cameras[i].component_id, summarize(outputs.cameras[i].metrics).c_str());
      }
      if (outputs.outside_in) {
        if (!outputs.cameras.empty()) std::printf("  combined (%d hand-overs):\n", outputs.hand_overs);
        std::printf("%s", summarize(*outputs.outside_in).c_str());
      }
      if (!outputs.cameras.empty()) {
        std::printf("  outputs: %s/{metrics.json, trajectory.png, errors.png, outside_in_metrics.json, handover.png, room.png, "
                    "camera_<i>/}\n", out.c_str());
      } else {
        std::printf("  outputs: %s/{metrics.json, trajectory.png, errors.png, %s, pose.csv, dataset/}\n", out.c_str(),
                    outputs.outside_in ? "outside_in_metrics.json" : "debug_frame_*.png");
      }
    } else if (survey_map->parsed()) {
      files.inputs({drawing_path, estimate_path});
      if (!truth_path.empty()) files.input(truth_path);
      files.output_file("--out", out);
      files.check();
      const irloc::MarkerMap drawing = irloc::hal::load_marker_map(drawing_path);
      const irloc::MarkerMap estimate = irloc::hal::load_marker_map(estimate_path);
      if (truth_path.empty()) {
        // A real run: each marker against where the survey started from.
        for (const irloc::DotMarker& marker : estimate.dot_markers) {
          const irloc::DotMarker* before = drawing.find_dot_marker(marker.id);
          if (before == nullptr) {
            std::printf("marker %4d: new\n", marker.id);
          } else {
            std::printf("marker %4d: moved %7.2f mm %7.3f deg\n", marker.id, 1e3 * (marker.origin - before->origin).norm(),
                        std::abs(irloc::wrap_angle(marker.yaw - before->yaw)) * 180 / std::numbers::pi);
          }
        }
        std::printf("irloc-sim survey-map: %zu markers before, %zu after; picture in %s\n", drawing.dot_markers.size(),
                    estimate.dot_markers.size(), out.c_str());
        plot_survey_map(out, drawing, estimate, nullptr);
      } else {
        const irloc::MarkerMap truth = irloc::hal::load_marker_map(truth_path);
        const SurveyCheck check = check_survey(estimate, truth);
        for (const SurveyMarkerError& marker : check.markers) {
          std::printf("marker %4d: %7.2f mm %7.3f deg\n", marker.id, 1e3 * marker.position_m,
                      marker.yaw_rad * 180 / std::numbers::pi);
        }
        std::printf("irloc-sim survey-map: %zu markers, max %.2f mm, %.3f deg; missing %zu, invented %zu; picture in %s\n",
                    check.markers.size(), 1e3 * check.max_position_m, check.max_yaw_rad * 180 / std::numbers::pi,
                    check.missing.size(), check.invented.size(), out.c_str());
        plot_survey_map(out, drawing, estimate, &truth);
      }
    } else if (ledmap->parsed()) {
      const Scenario scenario = scenario_from(scenario_path, 0);
      files.inputs(referenced_files(scenario));
      files.output_file("--out", out);
      files.check();
      HeatMap map = led_ring_brightness(scenario, half_extent, cells);
      map.title = "Retro brightness: " + std::filesystem::path(scenario.name).stem().string();
      const double peak = map.high;
      if (scale_max > 0) map.high = scale_max;
      plot_heat_map(out, map);
      std::printf("irloc-sim: LED ring brightness map in %s (peak %.1f %% of full scale)\n", out.c_str(), peak);
    } else if (coverage->parsed()) {
      const Scenario scenario = scenario_from(scenario_path, 0);
      files.inputs(referenced_files(scenario));
      files.output_file("--out", out);
      files.check();
      HeatMap map = landmark_coverage(scenario, cell, headings);
      const double fraction = coverage_fraction(map, k);
      char title[128];
      std::snprintf(title, sizeof title, "Landmarks in view at every heading (>= %d on %.0f %% of the floor)", k,
                    100 * fraction);
      map.title = title;
      plot_heat_map(out, map);
      std::printf("irloc-sim: coverage map in %s: %.1f %% of the floor sees >= %d landmarks at every heading\n",
                  out.c_str(), 100 * fraction, k);
    } else if (ledplan->parsed()) {
      const Scenario scenario = scenario_from(scenario_path, 0);
      files.inputs(referenced_files(scenario));
      files.output_file("--out", out);
      files.check();
      HeatMap map = led_position_error_map(scenario, cell, headings, pixel_sigma);
      std::size_t posed = 0;
      for (const double value : map.values) posed += std::isfinite(value) ? 1 : 0;
      const double fraction = map.values.empty() ? 0 : static_cast<double>(posed) / static_cast<double>(map.values.size());
      char title[160];
      std::snprintf(title, sizeof title, "LED position error, 1 sigma, worst heading (grey: no pose): %.0f %%",
                    100 * fraction);
      map.title = title;
      const double worst = map.high;
      if (scale_mm > 0) map.high = scale_mm;
      plot_heat_map(out, map);
      std::printf("irloc-sim: LED placement map in %s: %.1f %% of the floor gives a pose at every heading, "
                  "worst error there %.1f mm\n", out.c_str(), 100 * fraction, worst);
    } else if (fit_confidence->parsed()) {
      const ConfidenceFit fit = irloc::sim::fit_confidence(config_path, dataset_path);
      std::printf("# irloc-sim fit-confidence: %zu dot candidates of %s\n%s", fit.samples, dataset_path.c_str(),
                  grey_levels_yaml(fit.model).c_str());
    } else if (calibrate_mount->parsed()) {
      files.inputs(config_files(config_path));
      files.inputs(dataset_files(dataset_path));
      files.output_file("--out", mount_out);
      files.check();
      const MountCalibration mount = irloc::sim::calibrate_mount(config_path, dataset_path);
      write_mount(config_path, mount_out, mount);
      std::printf("irloc-sim calibrate-mount: %zu poses, turned %.1f rad, circle radius %.4f m (rms %.4f m); "
                  "mount xyz [%.4f, %.4f, %.4f] written to %s\n",
                  mount.poses, mount.fit.turned, mount.fit.radius, mount.fit.circle_rms, mount.fit.offset.x(),
                  mount.fit.offset.y(), mount.z, mount_out.c_str());
    } else if (plot_residuals->parsed()) {
      const std::filesystem::path dir(calibrated_dir);
      files.inputs({dir / "calib.yaml", dir / "residuals.csv"});
      files.output_file("--calibration", dir / "residuals.png");
      files.check();
      const irloc::CameraIntrinsics camera = irloc::hal::load_camera_info(dir / "calib.yaml");
      plot_calibration_residuals(dir / "residuals.png", read_calibration_residuals(dir / "residuals.csv"), camera.width,
                                 camera.height);
      std::printf("irloc-sim: residual picture in %s\n", (dir / "residuals.png").c_str());
    } else {
      std::fwrite(default_scenario_yaml().data(), 1, default_scenario_yaml().size(), stdout);
    }
    return 0;
  } catch (const irloc::hal::InputError& e) {
    std::fprintf(stderr, "irloc-sim: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irloc-sim: internal error: %s\n", e.what());
  }
  return 1;
}
