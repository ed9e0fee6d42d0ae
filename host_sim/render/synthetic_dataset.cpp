#include "host_sim/render/synthetic_dataset.hpp"

#include <algorithm>

#include "algo/core/image.hpp"
#include "io/files/output_file.hpp"
#include "io/dataset/dataset_writer.hpp"

namespace irloc::sim {
namespace {

constexpr std::int64_t kFramePeriodNs = 33'333'333;  // 30 fps

template <typename Pixel>
void fill_disc(ImageView<Pixel> image, double cx, double cy, double radius, Pixel value) {
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) image.at(x, y) = value;
    }
  }
}

// Dark ceiling, a lamp bright in every frame, marker dots bright only with the LEDs on.
template <typename Pixel>
void draw(ImageView<Pixel> image, bool led_on, Pixel bright) {
  std::fill(image.data(), image.data() + image.width() * image.height(), static_cast<Pixel>(bright / 16));
  fill_disc(image, image.width() * 0.8, image.height() * 0.2, image.height() * 0.06, bright);
  if (!led_on) return;
  const double pitch = image.height() * 0.06;
  const double x0 = image.width() * 0.4;
  const double y0 = image.height() * 0.4;
  for (const auto& [i, j] : {std::pair{0, 0}, {0, 3}, {3, 0}, {1, 1}, {2, 2}}) {
    fill_disc(image, x0 + j * pitch, y0 + i * pitch, pitch * 0.25, bright);
  }
}

}  // namespace

void write_synthetic_dataset(const std::filesystem::path& dir, const SyntheticDatasetOptions& options) {
  io::DatasetWriter writer(dir, 4095);
  Image8 image8(options.width, options.height);
  Image16 image16(options.width, options.height);
  for (int seq = 0; seq < options.frames; ++seq) {
    const auto useq = static_cast<std::uint64_t>(seq);
    if (std::find(options.dropped_seqs.begin(), options.dropped_seqs.end(), useq) != options.dropped_seqs.end()) continue;
    Frame frame;
    frame.seq = useq;
    frame.t_ns = 1'000'000'000 + seq * kFramePeriodNs;
    frame.led_on = seq % 2 == 0;
    if (options.sixteen_bit) {
      draw(image16.view(), frame.led_on, std::uint16_t{4000});
      frame.image = ImageView16(image16.view());
    } else {
      draw(image8.view(), frame.led_on, std::uint8_t{250});
      frame.image = ImageView8(image8.view());
    }
    writer.write(frame);
  }

  const double f = options.width * 0.9;
  io::replace_file_atomically(dir / "calib.yaml",
             "image_width: " + std::to_string(options.width) + "\nimage_height: " + std::to_string(options.height) +
                 "\ncamera_name: synthetic\ncamera_matrix:\n  rows: 3\n  cols: 3\n  data: [" + std::to_string(f) +
                 ", 0, " + std::to_string((options.width - 1) / 2.0) + ", 0, " + std::to_string(f) + ", " +
                 std::to_string((options.height - 1) / 2.0) +
                 ", 0, 0, 1]\ndistortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n"
                 "  data: [0, 0, 0, 0, 0]\n");
  io::replace_file_atomically(dir / "map.yaml", "dot_markers:\n  - id: 1782\n    origin: [1.0, 2.0, 2.6]\n    yaw: 0.0\n");
  io::replace_file_atomically(dir / "config.yaml",
             "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3], rpy: [0, 0, 0]}\n"
             "robot:\n  dof: 3\nmap: map.yaml\n");
}

}  // namespace irloc::sim
