// The real libcamera and libgpiod, linked and called, on a machine without a camera or a GPIO
// chip: each start-up failure is one clear io::InputError naming the device, never a crash.

#include <atomic>
#include <string>

#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "hal/linux/gpiod_strobe.hpp"
#include "hal/linux/libcamera_camera.hpp"

namespace irloc::hal {
namespace {

std::string error_of(auto&& open) {
  try {
    open();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DeviceAbsent, NoGpioChipIsOneLine) {
  const std::string message = error_of([] { GpiodStrobe strobe(GpioLine{"gpiochip-irloc-absent", 17, false}); });
  EXPECT_EQ(message, "strobe: gpiochip-irloc-absent: cannot open GPIO chip: No such file or directory");
}

TEST(DeviceAbsent, NoGpioChipByPathIsOneLine) {
  const std::string message = error_of([] { GpiodStrobe strobe(GpioLine{"/dev/gpiochip-irloc-absent", 4, true}); });
  EXPECT_EQ(message.rfind("strobe: /dev/gpiochip-irloc-absent: cannot open GPIO chip", 0), 0u) << message;
}

// This machine has no camera: libcamera starts and lists none (a camera attached later would
// make this test fail loudly rather than pass wrongly).
TEST(DeviceAbsent, NoCameraIsOneLine) {
  std::atomic<bool> stop{false};
  LibcameraSettings settings;
  settings.width = 640;
  settings.height = 480;
  const std::string message = error_of([&] { LibcameraCamera camera(settings, &stop); });
  EXPECT_EQ(message, "camera: no camera found (libcamera lists none; is it connected and enabled?)");
}

TEST(DeviceAbsent, NamedCameraIsNamedInTheError) {
  LibcameraSettings settings;
  settings.camera_id = "/base/soc/i2c0mux/i2c@1/imx219@10";
  settings.width = 820;
  settings.height = 616;
  const std::string message = error_of([&] { LibcameraCamera camera(settings, nullptr); });
  EXPECT_EQ(message.rfind("camera /base/soc/i2c0mux/i2c@1/imx219@10: ", 0), 0u) << message;
}

TEST(DeviceAbsent, UnknownPixelFormatIsRefusedBeforeAnyDevice) {
  LibcameraSettings settings;
  settings.width = 640;
  settings.height = 480;
  settings.formats = {"R8", "GREY16"};
  const std::string message = error_of([&] { LibcameraCamera camera(settings, nullptr); });
  EXPECT_EQ(message.rfind("camera: unknown pixel format 'GREY16'", 0), 0u) << message;
}

}  // namespace
}  // namespace irloc::hal
