#include "host_sim/render/dataset_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algo/core/image.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "io/files/output_file.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "host_sim/render/config_writer.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/render/renderer.hpp"

namespace irloc::sim {
namespace {

constexpr std::int64_t kStartNs = 1'000'000'000;

}  // namespace

void write_truth_csv(const std::filesystem::path& path, const std::vector<TruthRow>& rows) {
  std::string text = "seq,t_ns,x,y,z,roll,pitch,yaw\n";
  char line[512];
  for (const TruthRow& row : rows) {
    std::snprintf(line, sizeof line, "%llu,%lld,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n", static_cast<unsigned long long>(row.seq),
                  static_cast<long long>(row.t_ns), row.x, row.y, row.z, row.roll, row.pitch, row.yaw);
    text += line;
  }
  io::replace_file_atomically(path, text, 0644, "the truth");
}

std::int64_t frame_time_ns(const Scenario& scenario, std::uint64_t seq) {
  return kStartNs + static_cast<std::int64_t>(std::llround(static_cast<double>(seq) * 1e9 / scenario.camera.frame_rate));
}

bool is_dropped(const Scenario& scenario, std::uint64_t seq) {
  if ((seq / 2) % static_cast<std::uint64_t>(scenario.pair_stride) != 0) return true;
  if (std::find(scenario.dropped_frames.begin(), scenario.dropped_frames.end(), seq) != scenario.dropped_frames.end()) {
    return true;
  }
  if (scenario.drop_probability <= 0) return false;
  NoiseSource draw(mix_seed(scenario.seed, 0xD50Dull, seq));
  return draw.uniform() < scenario.drop_probability;
}

std::vector<TruthRow> render_dataset(const Scenario& scenario, const std::filesystem::path& dir,
                                     const Progress& progress) {
  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  const Sensor sensor(scenario.camera, scenario.seed);
  io::DatasetWriter writer(dir, sensor.max_value());
  write_replay_config(dir, scenario);

  const int width = renderer.width(), height = renderer.height();
  std::vector<float> radiance(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  Image8 image8(width, height);
  Image16 image16(width, height);
  const bool eight_bit = scenario.camera.bit_depth == 8;

  std::vector<TruthRow> truth;
  for (int index = 0; index < scenario.frames; ++index) {
    const auto seq = static_cast<std::uint64_t>(index);
    if (!is_dropped(scenario, seq)) {
      const double t = static_cast<double>(index) / scenario.camera.frame_rate;
      const bool led_on = seq % 2 == 0;
      renderer.render(t, led_on, radiance);
      for_each_row(height, [&](int y) {
        const std::span<const float> row(&radiance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width)],
                                         static_cast<std::size_t>(width));
        if (eight_bit) {
          sensor.expose_row(row, seq, y, image8.view().row(y));
        } else {
          sensor.expose_row(row, seq, y, image16.view().row(y));
        }
      });
      Frame frame;
      frame.seq = seq;
      frame.t_ns = frame_time_ns(scenario, seq);
      frame.led_on = led_on;
      if (eight_bit) {
        frame.image = ImageView8(image8.view());
      } else {
        frame.image = ImageView16(image16.view());
      }
      writer.write(frame);

      const Eigen::Isometry3d pose = renderer.trajectory().t_w_b(t);
      const RollPitchYaw rpy = rpy_from_rotation(pose.linear());
      truth.push_back({seq, frame.t_ns, led_on, pose.translation().x(), pose.translation().y(), pose.translation().z(),
                       rpy.roll, rpy.pitch, rpy.yaw});
    }
    if (progress) progress(index + 1, scenario.frames);
  }
  write_truth_csv(dir / "truth.csv", truth);
  return truth;
}

}  // namespace irloc::sim
