// libFuzzer target: irlocd --calibrate's input, the drive (algo/calibration/drive_calibration):
// arbitrary poses and dot pixels (each frame: 3 bytes of pose, then up to 8 dots of 3 bytes: the
// dot's world point on a 0.25 m ceiling grid and its pixel) for the perturbed camera of a 640 x 480
// plumb_bob lens. calibrate_from_drive must return (ok or a reason), never crash or hang, and an ok
// result is finite.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "algo/calibration/drive_calibration.hpp"
#include "algo/geometry/pose.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace irloc;
  CameraIntrinsics camera{640, 480, 400, 399, 322.4, 238.1, LensModel::plumb_bob, {-0.1, 0.02, 0, 0, 0}};
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = Eigen::Vector3d(0.1, 0.02, 0.3);
  calibration::DriveObservations drive(64);
  std::size_t at = 0;
  std::int64_t t_ns = 0;
  while (at + 3 <= size) {
    const RigidTransform pose{rotation_from_rpy(0, 0, (data[at + 2] - 128) * 0.05),
                              Eigen::Vector3d((data[at] - 128) * 0.02, (data[at + 1] - 128) * 0.02, 0)};
    at += 3;
    std::vector<PointObservation> dots;
    while (at + 3 <= size && dots.size() < 8 && data[at] != 0xff) {
      PointObservation dot;
      dot.landmark = data[at];
      dot.world = Eigen::Vector3d((data[at] % 16) * 0.25 - 2, (data[at] / 16) * 0.25 - 2, 2.6);
      dot.pixel = Eigen::Vector2d(data[at + 1] * 2.5, data[at + 2] * 1.9);
      dots.push_back(dot);
      at += 3;
    }
    if (at < size && data[at] == 0xff) ++at;
    drive.add(t_ns, pose, dots);
    t_ns += 66'000'000;
  }
  const calibration::CalibrationResult result = calibration::calibrate_from_drive(drive, camera, mount, {});
  if (result.ok && !(std::isfinite(result.camera.fx) && std::isfinite(result.camera.cx) && result.mount.translation.allFinite())) {
    std::abort();
  }
  return 0;
}
