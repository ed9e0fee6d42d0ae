// The device factories: which backend each spec gives, and what each backend tells the daemon
// through the interfaces (its own LEDs, its pixel ceiling) instead of a downcast.

#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "firmware/camera_source.hpp"
#include "firmware/serial_spec.hpp"
#include "firmware/strobe_source.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

CameraRequest small_request() {
  CameraRequest request;
  request.width = 64;
  request.height = 48;
  request.size_source = "calibration.yaml";
  return request;
}

TEST(DeviceFactories, SimulatedCameraDrivesItsOwnLedsAndDeliversTheAskedFrames) {
  const auto camera = open_camera("sim:3", small_request());
  ASSERT_NE(camera->built_in_strobe(), nullptr);
  EXPECT_EQ(camera->width(), 64);
  EXPECT_EQ(camera->height(), 48);
  Frame frame;
  int frames = 0;
  while (camera->next(frame)) ++frames;
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(open_strobe("sim:3", std::nullopt), nullptr);  // no GPIO line wanted
}

TEST(DeviceFactories, SimulatedCameraOptions) {
  // Unpaced: the default 60 fps pacing would take 5 s for 300 frames.
  const auto unpaced = open_camera("sim:300:unpaced", small_request());
  const auto started = std::chrono::steady_clock::now();
  Frame frame;
  int frames = 0;
  while (unpaced->next(frame)) ++frames;
  EXPECT_EQ(frames, 300);
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(4));

  // Stalled before frame 2: two frames, then next() waits until the stop request ends the stream.
  std::atomic<bool> stop{false};
  CameraRequest request = small_request();
  request.stop = &stop;
  const auto stalled = open_camera("sim:stall-at=2:unpaced", request);
  ASSERT_TRUE(stalled->next(frame));
  ASSERT_TRUE(stalled->next(frame));
  EXPECT_EQ(frame.seq, 1u);
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop.store(true);
  });
  const auto stall_started = std::chrono::steady_clock::now();
  EXPECT_FALSE(stalled->next(frame));
  EXPECT_GE(std::chrono::steady_clock::now() - stall_started, std::chrono::milliseconds(200));
  stopper.join();

  for (const char* bad : {"sim:5:fast", "sim:5:stall-at=", "sim:5:stall-at=x", "sim:unpaced:5", "sim::unpaced"}) {
    try {
      open_camera(bad, small_request());
      ADD_FAILURE() << bad << " was accepted";
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--camera ") + bad + ": expected sim[:FRAMES][:unpaced][:stall-at=SEQ]");
    }
  }
}

TEST(DeviceFactories, BadSimulatedFrameCountIsRefusedByName) {
  EXPECT_THROW(open_camera("sim:", small_request()), io::InputError);
  EXPECT_THROW(open_camera("sim:12x", small_request()), io::InputError);
  try {
    open_camera("usb:0", small_request());
    FAIL() << "an unknown camera kind was accepted";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--camera usb:0: unknown camera"), std::string::npos) << e.what();
  }
}

TEST(DeviceFactories, LiveCameraWithoutABoardStrobeIsRefusedBeforeAnyDeviceOpens) {
  try {
    open_strobe("libcamera", std::nullopt);
    FAIL() << "a live camera without a strobe was accepted";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs the LED strobe of a board file"), std::string::npos) << e.what();
  }
  EXPECT_EQ(open_strobe("dir:/some/dataset", std::nullopt), nullptr);  // frames labelled already
}

TEST(DeviceFactories, SerialNoneOpensNothingAndAMissingDeviceIsRefused) {
  EXPECT_EQ(open_serial(parse_serial_spec("none")), nullptr);
  EXPECT_THROW(open_serial(parse_serial_spec("/dev/irloc-absent-serial:115200")), io::InputError);
}

}  // namespace
}  // namespace irloc::firmware
