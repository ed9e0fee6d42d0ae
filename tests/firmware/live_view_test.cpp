// irlocd's live view in-process: the frame loop's publishing (only while viewed, allocation-free,
// never waiting), the HTTP server's pages and its answers to bad requests, the controls reaching
// the simulated camera, saving them to the file the next start reads, the token off loopback, and
// the offline drawing. The page in a real browser: live_view_browser_test.cpp.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <numeric>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "firmware/live/http_token.hpp"
#include "firmware/live/live_server.hpp"
#include "io/config/camera_settings_file.hpp"
#include "io/config/config_file.hpp"
#include "io/input_error.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "hal/sim/strobed_scene_camera.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
// After Eigen: httplib brings <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace irloc::firmware {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

class LiveView : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SyntheticDatasetOptions options;
    options.frames = 6;
    sim::write_synthetic_dataset(dir_.path(), options);
    io::RobotConfig config = io::load_robot_config(dir_ / "config.yaml");
    width_ = config.setup.camera.width;
    height_ = config.setup.camera.height;
    camera_.emplace(dir_.path(), width_, height_, "calib.yaml");
    localizer_.emplace(std::move(config.setup));
    slot_.emplace(width_, height_, 255);
  }

  // The next strobe pair of the dataset through the localizer and the publisher.
  PoseEstimate attempt(LivePublisher& publisher) {
    Frame frame;
    while (camera_->next(frame)) {
      if (const std::optional<StrobePair> pair = pairer_.push(frame)) {
        const PoseEstimate estimate = localizer_->process(*pair);
        publisher.on_attempt(*pair, std::nullopt, true, estimate);
        return estimate;
      }
    }
    ADD_FAILURE() << "the dataset ran out of pairs";
    return {};
  }

  std::unique_ptr<LiveServer> serve(LiveServerSettings settings = {}, LiveControlTargets targets = {}) {
    return std::make_unique<LiveServer>(settings, *slot_, live_view_geometry(*localizer_), targets);
  }

  test::TempDir dir_;
  int width_ = 0, height_ = 0;
  std::optional<hal::DatasetCamera> camera_;
  std::optional<Localizer> localizer_;
  StrobePairer pairer_;
  std::optional<LiveSlot> slot_;
};

TEST_F(LiveView, PublishesOnlyWhileViewedAndWithoutAllocating) {
  LivePublisher publisher(*slot_, *localizer_);
  attempt(publisher);
  EXPECT_EQ(slot_->publication(), 0u) << "nobody looked: nothing is copied";
  slot_->mark_viewed(LiveSlot::Clock::now());
  test::AllocationCounter counter;
  const PoseEstimate estimate = attempt(publisher);
  EXPECT_EQ(counter.count(), 0u);
  ASSERT_EQ(slot_->publication(), 1u);
  LiveSnapshot snapshot;
  slot_->read(snapshot);
  EXPECT_EQ(snapshot.estimate.seq, estimate.seq);
  EXPECT_TRUE(snapshot.has_off);
  ASSERT_EQ(snapshot.sources.size(), localizer_->last_results().size());
  for (std::size_t k = 0; k < snapshot.sources.size(); ++k) {
    EXPECT_STREQ(snapshot.sources[k].outcome, localizer_->last_results()[k].outcome);
  }
  // Rate-limited: the next attempt within a tenth of a second is not published.
  attempt(publisher);
  EXPECT_EQ(slot_->publication(), 1u);
}

TEST_F(LiveView, ABusySlotIsSkippedNotWaitedFor) {
  LivePublisher publisher(*slot_, *localizer_);
  slot_->mark_viewed(LiveSlot::Clock::now());
  LiveSnapshot copy;
  std::atomic<bool> reading{true};
  // The server thread holds the slot (a long copy) while the frame loop publishes.
  std::thread server([&] {
    while (reading.load()) slot_->read(copy);
  });
  const auto started = std::chrono::steady_clock::now();
  for (int k = 0; k < 2; ++k) attempt(publisher);
  reading.store(false);
  server.join();
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(2));
}

TEST_F(LiveView, ServesThePagePictureStateAndMap) {
  const std::unique_ptr<LiveServer> server = serve();
  httplib::Client client("127.0.0.1", server->port());
  httplib::Result page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_THAT(page->body, HasSubstr("irlocd live view"));
  EXPECT_THAT(page->body, ::testing::Not(HasSubstr("http://"))) << "the page loads nothing from elsewhere";
  httplib::Result early = client.Get("/frame.jpg");
  ASSERT_TRUE(early);
  EXPECT_EQ(early->status, 503);
  EXPECT_THAT(early->body, HasSubstr("no picture yet"));

  LivePublisher publisher(*slot_, *localizer_);
  const PoseEstimate estimate = attempt(publisher);  // viewed by the request above
  httplib::Result picture = client.Get("/frame.jpg?image=difference&width=160");
  ASSERT_TRUE(picture);
  ASSERT_EQ(picture->status, 200) << picture->body;
  EXPECT_EQ(picture->get_header_value("Content-Type"), "image/jpeg");
  EXPECT_EQ(picture->get_header_value("X-Irloc-Seq"), std::to_string(estimate.seq));
  const std::vector<std::uint8_t> bytes(picture->body.begin(), picture->body.end());
  const cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);  // an independent decoder
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.cols, 160);
  EXPECT_EQ(decoded.rows, height_ * 160 / width_ + 40);  // the banner above the picture

  httplib::Result state = client.Get("/state.json");
  ASSERT_TRUE(state);
  const json body = json::parse(state->body);
  EXPECT_EQ(body["pose"]["seq"], estimate.seq);
  EXPECT_EQ(body["pose"]["ok"], estimate.ok);
  ASSERT_EQ(body["sources"].size(), localizer_->last_results().size());
  EXPECT_EQ(body["sources"][0]["outcome"], localizer_->last_results()[0].outcome);
  EXPECT_EQ(body["counters"]["pose_attempts"], 0) << "the loop's counters: no loop watched here";
  EXPECT_TRUE(body["controls"]["writable"]);
  const json map = json::parse(client.Get("/map.json")->body);
  EXPECT_EQ(map["dot_markers"].size(), localizer_->setup().map.dot_markers.size());
}

TEST_F(LiveView, BadRequestsGetClearErrors) {
  const std::unique_ptr<LiveServer> server = serve();
  httplib::Client client("127.0.0.1", server->port());
  const auto expect = [](const httplib::Result& result, int status, const std::string& reason) {
    ASSERT_TRUE(result);
    EXPECT_EQ(result->status, status) << result->body;
    EXPECT_THAT(result->body, HasSubstr(reason));
  };
  expect(client.Get("/nothing-here"), 404, "/nothing-here: no such page");
  expect(client.Delete("/state.json"), 405, "DELETE /state.json: method not allowed (use GET)");
  expect(client.Get("/controls"), 405, "use POST");
  expect(client.Get("/frame.jpg?image=infrared"), 400, "image: expected on or difference, got 'infrared'");
  expect(client.Get("/frame.jpg?width=12"), 400, "width: expected a whole number of pixels in [64, 1920], got '12'");
  expect(client.Post("/controls", "{not json", "application/json"), 400, "body: expected a JSON object");
  expect(client.Post("/controls", R"({"shutter": 1})", "application/json"), 400, "shutter: unknown control");
  expect(client.Post("/controls", R"({"exposure_us": 1000})", "application/json"), 409,
         "exposure_us: this camera has no such control");
  expect(client.Post("/controls", R"({"leds": false})", "application/json"), 409, "leds: this camera's LEDs are not strobed");
  expect(client.Post("/controls", std::string(5000, ' '), "application/json"), 413, "larger than 4096 bytes");
  expect(client.Post("/controls/save", "", "text/plain"), 409, "started without --camera-settings");

  // A server of two connections (its own, so that no request above is still closing) with two
  // held open: a third is refused, then served again once they close.
  LiveServerSettings two_connections;
  two_connections.max_connections = 2;
  const std::unique_ptr<LiveServer> limited = serve(two_connections);
  std::vector<int> held;
  for (int k = 0; k < 2; ++k) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(limited->port()));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    held.push_back(fd);
  }
  // The server takes and drops connections as its threads get to them (later on a loaded
  // machine): GET `path` is asked again until its status is `status`, for at most 3 s.
  const auto answer_of = [&](const std::string& path, int status) {
    std::pair<int, std::string> answer{0, ""};
    for (int attempt = 0; attempt < 60 && answer.first != status; ++attempt) {
      if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
      const httplib::Result result = httplib::Client("127.0.0.1", limited->port()).Get(path);
      if (result) answer = {result->status, result->body};
    }
    return answer;
  };
  const auto [refused_status, refused_body] = answer_of("/state.json", 503);
  EXPECT_EQ(refused_status, 503) << refused_body;
  EXPECT_THAT(refused_body, HasSubstr("too many connections at once"));
  for (const int fd : held) ::close(fd);
  const auto [served_status, served_body] = answer_of("/", 200);
  EXPECT_EQ(served_status, 200) << served_body;
  EXPECT_THAT(served_body, HasSubstr("irlocd live view"));
}

TEST_F(LiveView, ControlsReachTheSimulatedCameraAndSaveForTheNextStart) {
  hal::StrobedSceneSettings scene;
  scene.frames = 100;
  hal::StrobedSceneCamera sim(scene);
  std::atomic<bool> leds{true};
  LiveServerSettings settings;
  settings.camera_settings = dir_ / "camera.yaml";
  const std::unique_ptr<LiveServer> server = serve(settings, {sim.controls(), &leds});
  httplib::Client client("127.0.0.1", server->port());
  // The mean of the frame's lower half: background only (the lamp is near the top, and the
  // reflectors stay dark without an LED command).
  const auto mean_of_next_frame = [&] {
    Frame frame;
    EXPECT_TRUE(sim.next(frame));
    const ImageView8 image = std::get<ImageView8>(frame.image);
    const ImageView8 lower = image.region(0, image.height() / 2, image.width(), image.height() / 2);
    double sum = 0;
    for (int y = 0; y < lower.height(); ++y) sum += std::accumulate(lower.row(y), lower.row(y) + lower.width(), 0.0);
    return sum / (lower.width() * lower.height());
  };
  const double before = mean_of_next_frame();

  httplib::Result out_of_range = client.Post("/controls", R"({"exposure_us": 4000, "analogue_gain": 99})", "application/json");
  ASSERT_TRUE(out_of_range);
  EXPECT_EQ(out_of_range->status, 400);
  EXPECT_EQ(out_of_range->body, "analogue_gain: must be in [1, 16], got 99\n");
  EXPECT_EQ(sim.current(hal::CameraControl::exposure_us), 2000) << "nothing applied from a refused request";

  httplib::Result applied = client.Post("/controls", R"({"exposure_us": 4000, "leds": false})", "application/json");
  ASSERT_TRUE(applied);
  ASSERT_EQ(applied->status, 200) << applied->body;
  EXPECT_FALSE(leds.load());
  const double after = mean_of_next_frame();
  EXPECT_EQ(sim.current(hal::CameraControl::exposure_us), 4000);
  EXPECT_NEAR(after / before, 2.0, 0.05) << "twice the exposure, twice the light";
  EXPECT_EQ(json::parse(client.Get("/state.json")->body)["controls"]["exposure_us"]["value"], 4000);

  httplib::Result saved = client.Post("/controls/save", "", "text/plain");
  ASSERT_TRUE(saved);
  ASSERT_EQ(saved->status, 200) << saved->body;
  const io::CameraSettings read_back = io::read_camera_settings(dir_ / "camera.yaml", sim.controls());
  EXPECT_EQ(read_back[hal::CameraControl::exposure_us], 4000);
  EXPECT_EQ(read_back[hal::CameraControl::analogue_gain], 1);
  EXPECT_FALSE(read_back.leds);
}

TEST_F(LiveView, ReadOnlyAndTokenGuardTheControls) {
  hal::StrobedSceneCamera sim(hal::StrobedSceneSettings{});
  LiveServerSettings read_only;
  read_only.read_only = true;
  {
    const std::unique_ptr<LiveServer> server = serve(read_only, {sim.controls(), nullptr});
    httplib::Client client("127.0.0.1", server->port());
    httplib::Result refused = client.Post("/controls", R"({"exposure_us": 3000})", "application/json");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 403);
    EXPECT_THAT(refused->body, HasSubstr("read-only (--http-read-only)"));
    EXPECT_FALSE(json::parse(client.Get("/state.json")->body)["controls"]["writable"]);
  }
  LiveServerSettings with_token;
  with_token.token = load_or_create_http_token(dir_ / "token");
  const std::unique_ptr<LiveServer> server = serve(with_token, {sim.controls(), nullptr});
  httplib::Client client("127.0.0.1", server->port());
  httplib::Result refused = client.Post("/controls", R"({"exposure_us": 3000})", "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 403);
  EXPECT_THAT(refused->body, HasSubstr("need the token"));
  httplib::Result wrong = client.Post("/controls", {{"X-Irloc-Token", "0123456789abcdef0123456789abcdef"}},
                                      R"({"exposure_us": 3000})", "application/json");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 403);
  httplib::Result accepted = client.Post("/controls", {{"X-Irloc-Token", *with_token.token}}, R"({"exposure_us": 3000})",
                                         "application/json");
  ASSERT_TRUE(accepted);
  EXPECT_EQ(accepted->status, 200) << accepted->body;
  EXPECT_EQ(sim.current(hal::CameraControl::exposure_us), 2000) << "applied at the camera's next frame";
  Frame frame;
  ASSERT_TRUE(sim.next(frame));
  EXPECT_EQ(sim.current(hal::CameraControl::exposure_us), 3000);
}

TEST(HttpToken, MadeOnceReadableOnlyByItsOwnerAndKept) {
  test::TempDir dir;
  const std::filesystem::path file = dir / "http-token";
  const std::string token = load_or_create_http_token(file);
  EXPECT_EQ(token.size(), 32u);
  EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos);
  struct stat status {};
  ASSERT_EQ(::stat(file.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0600u);
  EXPECT_EQ(load_or_create_http_token(file), token);
  EXPECT_NE(load_or_create_http_token(dir / "other"), token);
  ::chmod(file.c_str(), 0644);
  EXPECT_EQ(test::input_error_message([&] { load_or_create_http_token(file); }),
            file.string() + ": the live view's token may be read by other users: chmod 600 it");
}

TEST(HttpAddress, ParsedAndCheckedBeforeAnyWork) {
  EXPECT_EQ(parse_http_address("127.0.0.1:8080"), std::make_pair(std::string("127.0.0.1"), 8080));
  EXPECT_EQ(parse_http_address("[::1]:80"), std::make_pair(std::string("::1"), 80));
  EXPECT_EQ(parse_http_address("0.0.0.0:0"), std::make_pair(std::string("0.0.0.0"), 0));
  for (const char* bad : {"8080", "127.0.0.1", "127.0.0.1:", "127.0.0.1:99999", "::1:80", "robot.local:80", "1.2.3.4:8o"}) {
    EXPECT_THAT(test::input_error_message([&] { parse_http_address(bad); }), HasSubstr(std::string("--http ") + bad)) << bad;
  }
  EXPECT_TRUE(is_loopback_address("127.0.0.1"));
  EXPECT_TRUE(is_loopback_address("127.3.2.1"));
  EXPECT_TRUE(is_loopback_address("::1"));
  EXPECT_TRUE(is_loopback_address("localhost"));
  EXPECT_FALSE(is_loopback_address("0.0.0.0"));
  EXPECT_FALSE(is_loopback_address("192.168.1.20"));
  EXPECT_FALSE(is_loopback_address("::"));
}

TEST(CameraSettingsFile, BadValuesNameTheFileAndField) {
  test::TempDir dir;
  hal::StrobedSceneCamera sim(hal::StrobedSceneSettings{});
  const std::filesystem::path file = dir / "camera.yaml";
  std::ofstream(file) << "exposure_us: 3000\nanalogue_gain: 40\n";
  EXPECT_EQ(test::input_error_message([&] { io::read_camera_settings(file, sim.controls()); }),
            file.string() + ":2: analogue_gain: must be in [1, 16], got 40");
  std::ofstream(file) << "exposure: 3000\n";
  EXPECT_THAT(test::input_error_message([&] { io::read_camera_settings(file, sim.controls()); }), HasSubstr(":1: exposure"));
  std::ofstream(file) << "exposure_us: 3000\n";
  EXPECT_EQ(test::input_error_message([&] { io::read_camera_settings(file, nullptr); }),
            file.string() + ":1: exposure_us: this camera has no such control");
}

}  // namespace
}  // namespace irloc::firmware
