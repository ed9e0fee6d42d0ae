// The fault plan's syntax and the fault-injecting camera, on a camera of numbered frames.

#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hal/device_lost.hpp"
#include "io/input_error.hpp"
#include "hal/sim/fault_injecting_camera.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::hal {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& plan) {
  try {
    parse_fault_plan(plan);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FaultPlan, ReadsEveryKind) {
  const std::vector<Fault> faults = parse_fault_plan("lost@10+1500,late@20+300,drop@30+7,dark@40+5,desync@50+6,jump@60-3600");
  ASSERT_EQ(faults.size(), 6u);
  EXPECT_EQ(faults[0].kind, FaultKind::lost);
  EXPECT_EQ(faults[0].at_seq, 10u);
  EXPECT_EQ(faults[0].amount, 1500);
  EXPECT_EQ(faults[4].kind, FaultKind::desync);
  EXPECT_EQ(faults[5].kind, FaultKind::jump);
  EXPECT_EQ(faults[5].amount, -3600);
}

TEST(FaultPlan, RefusesWhatItCannotReadNamingTheItem) {
  EXPECT_EQ(error_of("lost@10+1500,fire@3+1"), "--inject-faults fire@3+1: unknown fault (expected lost, late, drop, dark, desync or jump)");
  EXPECT_EQ(error_of("late@20"), "--inject-faults late@20: expected KIND@SEQ+AMOUNT");
  EXPECT_EQ(error_of("late@x+20"), "--inject-faults late@x+20: SEQ must be a frame number");
  EXPECT_EQ(error_of("late@2+20ms"), "--inject-faults late@2+20ms: AMOUNT must be an integer");
  EXPECT_THAT(error_of("late@2+600000"), HasSubstr("AMOUNT must be 1 to 60000 ms"));
  EXPECT_THAT(error_of("drop@2-3"), HasSubstr("AMOUNT must be 1 to 1000000 frames"));
  EXPECT_THAT(error_of("jump@2+0"), HasSubstr("not 0"));
  EXPECT_THAT(error_of("drop@99999999999999999999+1"), HasSubstr("SEQ must be a frame number"));
  EXPECT_EQ(error_of(""), "--inject-faults : expected KIND@SEQ+AMOUNT");
  std::string many = "drop@1+1";
  for (int i = 0; i < 32; ++i) many += ",drop@1+1";
  EXPECT_EQ(error_of(many), "--inject-faults: at most 32 faults");
}

// Frames 0, 1, 2, ... whose every pixel is its sequence number; LED on for even ones; 1 ms apart
// from 20 s.
constexpr std::int64_t kStartNs = 20'000'000'000;
class NumberedCamera final : public Camera {
 public:
  int width() const override { return 4; }
  int height() const override { return 2; }
  bool next(Frame& frame) override {
    if (seq_ == 100) return false;
    std::vector<std::uint8_t>& pixels = slots_[seq_ % 3];
    std::fill(pixels.begin(), pixels.end(), static_cast<std::uint8_t>(seq_));
    frame.seq = seq_;
    frame.t_ns = kStartNs + static_cast<std::int64_t>(seq_) * 1'000'000;
    frame.led_on = seq_ % 2 == 0;
    frame.image = ImageView8(pixels.data(), 4, 2);
    ++seq_;
    return true;
  }

 private:
  std::uint64_t seq_ = 0;
  std::array<std::vector<std::uint8_t>, 3> slots_{std::vector<std::uint8_t>(8), std::vector<std::uint8_t>(8),
                                                  std::vector<std::uint8_t>(8)};
};

std::uint8_t first_pixel(const Frame& frame) { return std::get<ImageView8>(frame.image).at(0, 0); }

TEST(FaultInjectingCamera, DarkLedOnFramesShowTheLedOffFrameBefore) {
  FaultInjectingCamera camera(std::make_unique<NumberedCamera>(), parse_fault_plan("dark@4+3"));
  Frame frame;
  for (int k = 0; k < 8; ++k) {
    ASSERT_TRUE(camera.next(frame));
    EXPECT_EQ(frame.seq, static_cast<std::uint64_t>(k));
    EXPECT_EQ(frame.led_on, k % 2 == 0);  // the label stays: the LEDs were commanded on
    const int shown = (k == 4 || k == 6) ? k - 1 : k;
    EXPECT_EQ(first_pixel(frame), shown) << k;
  }
}

TEST(FaultInjectingCamera, DropsDesyncsAndShiftsTheClock) {
  FaultInjectingCamera camera(std::make_unique<NumberedCamera>(), parse_fault_plan("drop@2+3,desync@6+2,jump@7-10"));
  Frame frame;
  std::vector<std::uint64_t> seqs;
  std::vector<bool> labels;
  std::vector<std::int64_t> times;
  for (int k = 0; k < 6; ++k) {
    ASSERT_TRUE(camera.next(frame));
    seqs.push_back(frame.seq);
    labels.push_back(frame.led_on);
    times.push_back(frame.t_ns);
  }
  EXPECT_EQ(seqs, (std::vector<std::uint64_t>{0, 1, 5, 6, 7, 8}));
  EXPECT_EQ(labels, (std::vector<bool>{true, false, false, false, true, true}));
  EXPECT_EQ(times[3], kStartNs + 6'000'000);
  EXPECT_EQ(times[4], kStartNs + 7'000'000 - 10'000'000'000);
}

// The clock starts at 20 s: 10 s back and 15 more take it below 0, refused at the first frame.
TEST(FaultInjectingCamera, JumpsBelowZeroAreRefusedAtTheFirstFrame) {
  FaultInjectingCamera camera(std::make_unique<NumberedCamera>(), parse_fault_plan("jump@90-15,jump@7-10"));
  Frame frame;
  try {
    camera.next(frame);
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_STREQ(e.what(), "--inject-faults jump@90-15: takes the frame clock below 0 (the camera's first frame is at 20000 ms; "
                           "a monotonic clock counts from its start)");
  }
}

TEST(FaultInjectingCamera, ALostCameraComesBackAfterItsTimeAndSkipsWhatItMissed) {
  FaultInjectingCamera camera(std::make_unique<NumberedCamera>(), parse_fault_plan("lost@3+20"));
  Frame frame;
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(camera.next(frame));
  EXPECT_THROW(camera.next(frame), DeviceLost);
  EXPECT_THROW(camera.next(frame), DeviceLost);
  EXPECT_FALSE(camera.reopen());  // not yet: 20 ms
  std::this_thread::sleep_for(std::chrono::milliseconds(25));
  EXPECT_TRUE(camera.reopen());
  ASSERT_TRUE(camera.next(frame));
  EXPECT_EQ(frame.seq, 23u);  // exposed 20 ms after frame 3 (1 ms per frame)
}

TEST(FaultInjectingCamera, PassingFramesThroughAllocatesNothing) {
  FaultInjectingCamera camera(std::make_unique<NumberedCamera>(), parse_fault_plan("dark@10+20,drop@40+3,jump@50+1"));
  Frame frame;
  ASSERT_TRUE(camera.next(frame));
  test::AllocationCounter counter;
  while (camera.next(frame)) {
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace irloc::hal
