// irlocd's live view in a real browser: Debian's headless Chromium loads the page from irlocd
// (--http on loopback) and the test reads the page as the browser left it (--dump-dom):
//   - on a replayed rendered drive: pictures arrive and change, and the pose the page shows is
//     the pose CSV's row of the same frame;
//   - on the simulated camera (--camera sim, whose scene has no marker): each attempt shows the
//     outcome of the frame without a pose, and an exposure change reaches the camera.

#include <signal.h>

#include <chrono>
#include <numbers>
#include <regex>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/firmware/loop_drive.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"
// After Eigen: httplib brings <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace irloc {
namespace {

using ::testing::HasSubstr;

// irlocd with the live view on a free loopback port; the page's address once it serves.
class LiveIrlocd {
 public:
  LiveIrlocd(std::vector<std::string> arguments, const std::filesystem::path& dir) : stderr_file_(dir / "irlocd.txt") {
    arguments.insert(arguments.begin(), IRLOCD_PATH);
    arguments.insert(arguments.end(), {"--http", "127.0.0.1:0"});
    test::ChildOptions options;
    options.stderr_file = stderr_file_;
    process_.emplace(std::move(arguments), options);
    const std::regex served(R"(irlocd: live view on (http://127\.0\.0\.1:(\d+)/))");
    for (int k = 0; k < 600 && url_.empty() && process_->running(); ++k) {
      std::smatch match;
      const std::string text = test::read_text(stderr_file_);
      if (std::regex_search(text, match, served)) {
        url_ = match[1];
        port_ = std::stoi(match[2]);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ~LiveIrlocd() {
    if (process_->running()) process_->signal(SIGTERM);
    process_->wait();
  }
  const std::string& url() const { return url_; }
  int port() const { return port_; }
  std::string log() const { return test::read_text(stderr_file_); }

 private:
  std::filesystem::path stderr_file_;
  std::optional<test::ChildProcess> process_;
  std::string url_;
  int port_ = 0;
};

// The page as the browser's DOM after `seconds` of the page's own time (Chromium's virtual time,
// which waits for requests under way: about as long in real time here).
std::string page_in_browser(const std::string& url, const std::filesystem::path& dir, int seconds) {
  const std::filesystem::path dom = dir / "dom.html";
  test::ChildOptions options;
  options.stdout_file = dom;
  options.stderr_file = dir / "chromium.txt";
  test::ChildProcess browser({"/usr/bin/chromium", "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                              "--disable-component-update", "--disable-sync", "--no-first-run",
                              "--user-data-dir=" + (dir / "profile").string(), "--virtual-time-budget=" + std::to_string(seconds * 1000),
                              "--dump-dom", url},
                             options);
  EXPECT_EQ(browser.wait(), 0) << test::read_text(dir / "chromium.txt");
  return test::read_text(dom);
}

// The text of the element with this id.
std::string element_text(const std::string& dom, const std::string& id) {
  std::smatch match;
  if (!std::regex_search(dom, match, std::regex("id=\"" + id + "\"[^>]*>([^<]*)<"))) return "";
  return match[1];
}

TEST(LiveViewBrowser, ReplayShowsChangingPicturesAndThePoseCsvPose) {
  test::TempDir dir;
  // Six seconds of drive at 6 fps (a replay watched in the live view runs at its recorded pace):
  // the page looks at it for four.
  const sim::Scenario scenario = sim::parse_scenario(test::loop_drive_scenario(36, 9, 6).yaml(), "scenario.yaml");
  sim::render_dataset(scenario, dir / "dataset");
  const std::filesystem::path pose_csv = dir / "pose.csv";
  std::string dom;
  {
    LiveIrlocd irlocd({"--config", (dir / "dataset" / "config.yaml").string(), "--camera", "dir:" + (dir / "dataset").string(),
                       "--serial", "none", "--pose-csv", pose_csv.string()},
                      dir.path());
    ASSERT_FALSE(irlocd.url().empty()) << irlocd.log();
    dom = page_in_browser(irlocd.url(), dir.path(), 4);
  }
  ASSERT_THAT(dom, HasSubstr("irlocd live view"));
  EXPECT_GE(std::stoi(element_text(dom, "image-changes")), 2) << "pictures arrive and change";
  EXPECT_THAT(dom, ::testing::ContainsRegex("<img id=\"picture\"[^>]*src=\"blob:"));

  // The last pose the page showed, against the pose CSV's row of that frame.
  std::smatch match;
  const std::string last_pose = element_text(dom, "last-pose");
  ASSERT_TRUE(std::regex_search(last_pose, match, std::regex(R"(seq (\d+): x (\S+) y (\S+) z (\S+) yaw (\S+))"))) << last_pose;
  const std::uint64_t seq = std::stoull(match[1]);
  const std::vector<PoseEstimate> poses = sim::read_pose_csv(pose_csv);
  const auto row = std::find_if(poses.begin(), poses.end(), [&](const PoseEstimate& p) { return p.seq == seq; });
  ASSERT_NE(row, poses.end()) << "seq " << seq;
  ASSERT_TRUE(row->ok);
  EXPECT_NEAR(std::stod(match[2]), row->x, 1e-4);
  EXPECT_NEAR(std::stod(match[3]), row->y, 1e-4);
  EXPECT_NEAR(std::stod(match[4]), row->z, 1e-4);
  EXPECT_NEAR(std::stod(match[5]), row->yaw * 180 / std::numbers::pi, 0.01);
}

TEST(LiveViewBrowser, SimulatedCameraShowsWhyNotAndTakesAnExposureChange) {
  test::TempDir dir;
  sim::SyntheticDatasetOptions options;
  options.frames = 2;
  sim::write_synthetic_dataset(dir / "synthetic", options);
  LiveIrlocd irlocd({"--config", (dir / "synthetic" / "config.yaml").string(), "--camera", "sim", "--serial", "none"}, dir.path());
  ASSERT_FALSE(irlocd.url().empty()) << irlocd.log();
  httplib::Client client("127.0.0.1", irlocd.port());
  httplib::Result changed = client.Post("/controls", R"({"exposure_us": 4000})", "application/json");
  ASSERT_TRUE(changed);
  ASSERT_EQ(changed->status, 200) << changed->body;
  const std::string dom = page_in_browser(irlocd.url(), dir.path(), 3);
  ASSERT_THAT(dom, HasSubstr("irlocd live view"));
  EXPECT_GE(std::stoi(element_text(dom, "image-changes")), 2);
  EXPECT_EQ(element_text(dom, "pose-status"), "none");
  // The simulated scene has lamps and reflector spots but no marker: why not, per source.
  EXPECT_THAT(element_text(dom, "last-none"), ::testing::MatchesRegex("seq [0-9]+: dot: .+"));
  // The page's control shows the value the camera took its last frame with.
  EXPECT_THAT(dom, ::testing::ContainsRegex("id=\"control-exposure_us\"[^>]*data-current=\"4000\""));
}

}  // namespace
}  // namespace irloc
