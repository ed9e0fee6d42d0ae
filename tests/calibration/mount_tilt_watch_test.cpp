// The online watch of the mount's tilt on synthetic drives under a grid of dot markers: the dots
// projected through the true camera and mount with pixel noise, the poses those of the dot path
// with the believed calibration (synthetic_drive.hpp).

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "tests/calibration/synthetic_drive.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// The wheeled drive, driven `laps` times one after the other.
std::vector<TimedPose> laps(int count) {
  const std::vector<TimedPose> lap = wheeled_drive();
  std::vector<TimedPose> drive;
  const double period = lap.back().t + kFramePeriod;
  for (int k = 0; k < count; ++k) {
    for (TimedPose pose : lap) {
      pose.t += k * period;
      drive.push_back(pose);
    }
  }
  return drive;
}

RigidTransform knocked(double roll, double pitch) {
  RigidTransform mount = true_mount();
  mount.rotation = rotation_from_rpy(roll, pitch, 0) * mount.rotation;
  return mount;
}

struct WatchRun {
  calibration::MountTilt last;
  int changes = 0;
  double first_warning_t = -1;  // s
};

void feed(calibration::MountTiltWatch& watch, const SyntheticDrive& drive, WatchRun& run) {
  const calibration::DriveObservations& observations = drive.observations;
  for (const calibration::DriveFrame& frame : observations.frames()) {
    const bool changed = watch.update(frame.t_ns, frame.world_from_base, observations.observations().subspan(frame.first, frame.count));
    run.changes += changed;
    if (changed && watch.state().warning && run.first_warning_t < 0) run.first_warning_t = static_cast<double>(frame.t_ns) * 1e-9;
  }
  run.last = watch.state();
}

WatchRun watch(const SyntheticDrive& drive) {
  calibration::MountTiltWatch watch(true_camera(), true_mount(), Dof::planar3, {});
  WatchRun run;
  feed(watch, drive, run);
  return run;
}

TEST(MountTiltWatch, QuietWithTheTrueMount) {
  const SyntheticDrive drive =
      observe_drive(laps(3), marker_grid(), true_camera(), true_mount(), true_camera(), true_mount(), 0.3, 5);
  const WatchRun run = watch(drive);
  std::printf("true mount: tilt %.4f deg, sigma %.4f deg, %llu poses\n", run.last.magnitude() / kDegree,
              run.last.sigma() / kDegree, static_cast<unsigned long long>(run.last.poses));
  EXPECT_EQ(run.changes, 0);
  EXPECT_FALSE(run.last.warning);
  EXPECT_LT(run.last.magnitude(), 0.05 * kDegree);
  EXPECT_GT(run.last.poses, 500u);
}

TEST(MountTiltWatch, WarnsWhenTheCameraWasKnockedByADegree) {
  // The camera really sits 0.8 deg rolled and 0.6 deg pitched off the calibrated mount.
  const RigidTransform mount = knocked(0.8 * kDegree, -0.6 * kDegree);
  const SyntheticDrive drive = observe_drive(laps(2), marker_grid(), true_camera(), mount, true_camera(), true_mount(), 0.3, 6);
  const WatchRun run = watch(drive);
  std::printf("knocked 1 deg: warning after %.1f s; tilt %.3f deg (roll %.3f, pitch %.3f), sigma %.4f deg\n",
              run.first_warning_t, run.last.magnitude() / kDegree, run.last.tilt.x() / kDegree,
              run.last.tilt.y() / kDegree, run.last.sigma() / kDegree);
  EXPECT_TRUE(run.last.warning);
  EXPECT_EQ(run.changes, 1);
  ASSERT_GE(run.first_warning_t, 0);
  EXPECT_LT(run.first_warning_t, 30.0);
  EXPECT_NEAR(run.last.tilt.x(), 0.8 * kDegree, 0.1 * kDegree);
  EXPECT_NEAR(run.last.tilt.y(), -0.6 * kDegree, 0.1 * kDegree);
}

TEST(MountTiltWatch, AKnockDuringTheRunIsReportedWithinHalfAMinute) {
  // Two laps as calibrated, then the camera is knocked 1 deg in pitch and the robot drives on.
  const std::vector<TimedPose> before = laps(2);
  std::vector<TimedPose> after = laps(2);
  const double knock_t = before.back().t + kFramePeriod;
  for (TimedPose& pose : after) pose.t += knock_t;
  calibration::MountTiltWatch watch(true_camera(), true_mount(), Dof::planar3, {});
  WatchRun run;
  feed(watch, observe_drive(before, marker_grid(), true_camera(), true_mount(), true_camera(), true_mount(), 0.3, 9), run);
  EXPECT_FALSE(run.last.warning);
  feed(watch, observe_drive(after, marker_grid(), true_camera(), knocked(0, 1.0 * kDegree), true_camera(), true_mount(), 0.3, 10),
       run);
  std::printf("knocked 1 deg after %.0f s of driving: warning %.1f s after the knock; tilt %.3f deg\n", knock_t,
              run.first_warning_t - knock_t, run.last.magnitude() / kDegree);
  EXPECT_TRUE(run.last.warning);
  EXPECT_EQ(run.changes, 1);
  EXPECT_GT(run.first_warning_t, knock_t);
  EXPECT_LT(run.first_warning_t - knock_t, 30.0);
}

TEST(MountTiltWatch, UnderTheToleranceNoWarning) {
  // 0.1 deg off: within the default tolerance (0.2 deg), however long the drive.
  const SyntheticDrive drive =
      observe_drive(laps(3), marker_grid(), true_camera(), knocked(0, 0.1 * kDegree), true_camera(), true_mount(), 0.3, 7);
  const WatchRun run = watch(drive);
  EXPECT_EQ(run.changes, 0);
  EXPECT_NEAR(run.last.tilt.y(), 0.1 * kDegree, 0.03 * kDegree);
}

TEST(MountTiltWatch, UpdatesAllocateNothing) {
  const SyntheticDrive drive =
      observe_drive(wheeled_drive(), marker_grid(), true_camera(), true_mount(), true_camera(), true_mount(), 0.3, 8);
  calibration::MountTiltWatch watch(true_camera(), true_mount(), Dof::planar3, {});
  const calibration::DriveObservations& observations = drive.observations;
  AllocationCounter counter;
  for (const calibration::DriveFrame& frame : observations.frames()) {
    watch.update(frame.t_ns, frame.world_from_base, observations.observations().subspan(frame.first, frame.count));
  }
  EXPECT_EQ(counter.count(), 0u);
}

TEST(MountTiltWatch, RefusesDofSix) {
  EXPECT_THROW(calibration::MountTiltWatch(true_camera(), true_mount(), Dof::full6, {}), std::invalid_argument);
}

}  // namespace
}  // namespace irloc::test
