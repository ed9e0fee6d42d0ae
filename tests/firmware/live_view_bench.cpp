// The frame loop's time per frame with irlocd's live view: without it, with its server up and
// nobody looking, and with two viewers polling as the page does (a picture four times a second and
// the state twice a second, each); and the bandwidth one viewer takes. The frames come from memory
// (a rendered drive of the loop under three dot markers, 640 x 480), the loop runs unpaced.
// `make bench` writes build/bench/live_view.json; counters: ms_per_frame, viewer_kbit_per_s.

#include <atomic>
#include <chrono>
#include <thread>

#include <benchmark/benchmark.h>

#include "firmware/live/live_server.hpp"
#include "io/config/config_file.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/firmware/loop_drive.hpp"
#include "tests/support/temp_dir.hpp"
// After Eigen: httplib brings <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace irloc::firmware {
namespace {

// The drive's frames, rendered once, delivered again and again with increasing seq.
class MemoryCamera final : public hal::Camera {
 public:
  explicit MemoryCamera(const std::filesystem::path& dataset) {
    const io::RobotConfig config = io::load_robot_config(dataset / "config.yaml");
    width_ = config.setup.camera.width;
    height_ = config.setup.camera.height;
    hal::DatasetCamera camera(dataset, width_, height_, "calib.yaml");
    Frame frame;
    while (camera.next(frame)) {
      const ImageView8 image = std::get<ImageView8>(frame.image);
      pixels_.emplace_back(image.data(), image.data() + static_cast<std::ptrdiff_t>(width_) * height_);
      led_on_.push_back(frame.led_on);
    }
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  int maxval() const override { return 255; }
  bool next(Frame& frame) override {
    const std::size_t k = seq_ % pixels_.size();
    frame.seq = seq_;
    frame.t_ns = static_cast<std::int64_t>(seq_) * 33'333'333;
    frame.led_on = led_on_[k];
    frame.image = ImageView8(pixels_[k].data(), width_, height_);
    ++seq_;
    return true;
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::vector<std::uint8_t>> pixels_;
  std::vector<bool> led_on_;
  std::uint64_t seq_ = 0;
};

const std::filesystem::path& drive() {
  static test::TempDir dir;
  static const bool rendered = [] {
    sim::render_dataset(sim::parse_scenario(test::loop_drive_scenario(60, 11).yaml(), "scenario.yaml"), dir / "dataset");
    return true;
  }();
  (void)rendered;
  static const std::filesystem::path dataset = dir / "dataset";
  return dataset;
}

// A page's polling: pictures at 4 Hz, the state at 2 Hz; counts the bytes it receives.
class Viewer {
 public:
  explicit Viewer(int port) : thread_([this, port] { run(port); }) {}
  ~Viewer() {
    stop_.store(true);
    thread_.join();
  }
  double kbit_per_s() const { return static_cast<double>(bytes_.load()) * 8 / 1000 / seconds_.load(); }

 private:
  void run(int port) {
    httplib::Client client("127.0.0.1", port);
    client.set_keep_alive(true);
    const auto start = std::chrono::steady_clock::now();
    for (int tick = 0; !stop_.load(); ++tick) {
      if (httplib::Result r = client.Get("/frame.jpg?image=on&width=480")) bytes_ += r->body.size();
      if (tick % 2 == 0) {
        if (httplib::Result r = client.Get("/state.json")) bytes_ += r->body.size();
      }
      std::this_thread::sleep_until(start + std::chrono::milliseconds(250) * (tick + 1));
      seconds_.store(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  }

  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> bytes_{0};
  std::atomic<double> seconds_{1e-9};
  std::thread thread_;
};

// Argument: -1 no live view; 0 its server up, nobody looking; 2 two viewers.
void frame_loop_with_viewers(benchmark::State& state) {
  const int viewers = static_cast<int>(state.range(0));
  MemoryCamera camera(drive());
  io::RobotConfig config = io::load_robot_config(drive() / "config.yaml");
  Localizer localizer(std::move(config.setup));
  LiveSlot slot(camera.width(), camera.height(), camera.maxval());
  LivePublisher publisher(slot, localizer);
  FrameLoopIo io;
  if (viewers >= 0) io.attempts.add(&publisher);
  FrameLoop loop(camera, localizer, io, std::nullopt);
  publisher.watch(loop);
  std::unique_ptr<LiveServer> server;
  if (viewers >= 0) server = std::make_unique<LiveServer>(LiveServerSettings{}, slot, live_view_geometry(localizer), LiveControlTargets{});
  std::vector<std::unique_ptr<Viewer>> watching;
  for (int k = 0; k < viewers; ++k) watching.push_back(std::make_unique<Viewer>(server->port()));
  for (int k = 0; k < 60; ++k) loop.step();  // the viewers connect, the first pictures are drawn
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t frames = 0;
  for (auto _ : state) {
    loop.step();
    ++frames;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  state.counters["ms_per_frame"] = 1e3 * seconds / static_cast<double>(frames);
  if (!watching.empty()) state.counters["viewer_kbit_per_s"] = watching.front()->kbit_per_s();
}
BENCHMARK(frame_loop_with_viewers)->Arg(-1)->Arg(0)->Arg(2)->MinTime(5)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc::firmware

BENCHMARK_MAIN();
