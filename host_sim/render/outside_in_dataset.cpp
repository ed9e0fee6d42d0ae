#include "host_sim/render/outside_in_dataset.hpp"

#include <deque>
#include <sstream>

#include "io/files/output_file.hpp"
#include "io/config/camera_info_writer.hpp"
#include "io/input_error.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "host_sim/render/floor_reference.hpp"
#include "host_sim/render/outside_in_renderer.hpp"
#include "host_sim/scenario/trajectory.hpp"

namespace irloc::sim {
namespace {

std::string corners_yaml(const std::vector<Eigen::Vector2d>& corners) {
  std::string text = "[";
  for (std::size_t i = 0; i < corners.size(); ++i) {
    text += (i ? ", [" : "[") + io::yaml_number(corners[i].x()) + ", " + io::yaml_number(corners[i].y()) + "]";
  }
  return text + "]";
}

void write_outside_in_config(const std::filesystem::path& dir, const OutsideInSpec& spec, const WallCameraSpec& camera,
                             const outside_in::FloorReference& reference) {
  io::replace_file_atomically(dir / "calib.yaml", io::camera_info_yaml(camera.intrinsics, "irloc_sim_wall",
                                                       "Written by irloc-sim from the scenario's wall camera."));
  io::replace_file_atomically(dir / "config.yaml",
             "# Written by irloc-sim: replay with\n#   irlocd --config config.yaml --camera dir:. --serial none --component-id " +
                 std::to_string(camera.component_id) +
                 "\nmode: outside_in\ncamera:\n  calibration: calib.yaml\n  line_time_ns: " + std::to_string(camera.line_time_ns) +
                 "\n  floor_reference:\n    world: " +
                 corners_yaml(reference.world) + "\n    pixels: " + corners_yaml(reference.pixels) +
                 "\nrobot:\n  dof: 3\n  body: {length: " + io::yaml_number(spec.body_length) +
                 ", width: " + io::yaml_number(spec.body_width) + ", height: " + io::yaml_number(spec.body_height) + "}\n");
}

double lamp_at(const OutsideInSpec& spec, int frame) {
  double lamp = 1;
  for (const LightStep& step : spec.light_steps) {
    if (step.frame <= frame) lamp = step.lamp;
  }
  return lamp;
}

}  // namespace

WallCamera wall_camera_of(const WallCameraSpec& spec) {
  WallCamera camera;
  camera.intrinsics = spec.intrinsics;
  camera.height = spec.wall_height;
  camera.pitch_deg = spec.pitch_deg;
  camera.position = spec.wall_position;
  camera.yaw_deg = spec.yaw_deg;
  return camera;
}

std::vector<std::vector<OutsideInTruth>> render_outside_in_datasets(const Scenario& scenario,
                                                                    const std::vector<std::filesystem::path>& dirs,
                                                                    const Progress& progress) {
  if (!scenario.outside_in) throw io::InputError(scenario.name + ": not an outside-in scenario (kind: outside_in)");
  const OutsideInSpec& spec = *scenario.outside_in;
  if (dirs.size() != spec.cameras.size()) throw io::InputError(scenario.name + ": one dataset folder per camera expected");
  std::deque<io::DatasetWriter> writers;  // not movable
  std::vector<SceneRenderer> renderers;
  for (std::size_t i = 0; i < spec.cameras.size(); ++i) {
    const WallCameraSpec& camera = spec.cameras[i];
    writers.emplace_back(dirs[i]);
    write_outside_in_config(dirs[i], spec, camera, measured_floor_reference(wall_camera_of(camera), camera.floor_reference));
    // Each camera its own sensor noise.
    renderers.emplace_back(wall_camera_of(camera), outside_in::BoxBody{spec.body_length, spec.body_width, spec.body_height},
                           static_cast<unsigned>(scenario.seed + i));
    renderers.back().auto_exposure = camera.auto_exposure;
    renderers.back().noise_sigma = camera.noise_sigma;
    renderers.back().look = spec.look;
  }
  const Trajectory trajectory(scenario.trajectory);
  std::vector<std::vector<OutsideInTruth>> truth(spec.cameras.size());
  std::vector<TruthRow> rows;
  for (int index = 0; index < scenario.frames; ++index) {
    const auto seq = static_cast<std::uint64_t>(index);
    const double t = index / scenario.camera.frame_rate;
    // The scene at t + dt: the robot and the person move, the light is the frame's.
    SceneState scene;
    scene.lamp = lamp_at(spec, index);
    const double progress_of_run = scenario.frames > 1 ? double(index) / (scenario.frames - 1) : 0;
    scene.sun = spec.sun_from + progress_of_run * (spec.sun_to - spec.sun_from);
    scene.sun_strength = spec.sun_strength;
    const auto scene_at = [&](double dt) {
      const PlanarPose pose = trajectory.pose_at(t + dt);
      scene.robot = outside_in::FloorPose{pose.x, pose.y, pose.yaw};
      if (!scenario.people.empty()) {
        const Occluder& person = scenario.people.front();
        scene.person = Person{occluder_position(person, t + dt), person.radius, person.height};
      }
      return scene;
    };
    const PlanarPose pose = trajectory.pose_at(t);
    const TruthRow row{seq, frame_time_ns(scenario, seq), false, pose.x, pose.y, 0, 0, 0, pose.yaw};
    rows.push_back(row);
    for (std::size_t i = 0; i < renderers.size(); ++i) {
      FrameTruth frame_truth;
      // A rolling shutter: row v is exposed v * line_time after the frame's time.
      const double line_time = static_cast<double>(spec.cameras[i].line_time_ns) * 1e-9;
      const std::vector<std::uint8_t>& pixels =
          renderers[i].render([&](int v) { return scene_at(v * line_time); }, frame_truth);
      const CameraIntrinsics& k = spec.cameras[i].intrinsics;
      writers[i].write(Frame{seq, row.t_ns, false, ImageView8(pixels.data(), k.width, k.height)});
      truth[i].push_back({row, frame_truth.robot_whole_in_view, frame_truth.hidden_fraction()});
    }
    if (progress) progress(index + 1, scenario.frames);
  }
  for (const std::filesystem::path& dir : dirs) write_truth_csv(dir / "truth.csv", rows);
  return truth;
}

}  // namespace irloc::sim
