#pragma once
// The one shape of every pose source (dot markers, square tape markers, LED landmarks, ...):
// made once at start-up from the camera, the mount, the robot's dof and the map; then, per pose
// attempt, one checked input in and one SourceResult out.
//
//   std::unique_ptr<PoseSource> source =
//       std::make_unique<dot::DotMarkerSource>(source_setup, localizer_setup.dot);  // start-up
//   source->process(input, result);                                              // per frame
//
// The Localizer (algo/pipeline) holds any number of them and fuses their results by their
// covariances. A new source is a new folder with a class implementing this interface and one
// line in algo/pipeline/source_registry.cpp. Every source is alike in shape: its code in
// algo/markers/NAME/ and namespace irloc::NAME; its outcomes an enum with their text
// (NAME_outcome.hpp: DotOutcome, SquareOutcome, LedOutcome, OutsideInOutcome), set through
// SourceResult::set_outcome; what its last process() saw, its own type, from last_diagnostics().

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/source/source_input.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

// What every source is set up with; it lives as long as the Localizer that made the sources.
struct SourceSetup {
  const CameraIntrinsics& camera;
  const RigidTransform& base_from_camera;  // the mount T_B_C
  Dof dof;
  const MarkerMap& map;
  // Significant bits of the camera's pixels: frames are 8-bit for 8, 16-bit above (the config's
  // camera.pixel_bits). Sources size their per-frame images for this depth only.
  int pixel_bits = 8;
};

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  PoseSource() = default;
  // Sources hold per-frame buffers that their stages reference: they stay where they were made.
  PoseSource(const PoseSource&) = delete;
  PoseSource& operator=(const PoseSource&) = delete;

  virtual SourceKind kind() const = 0;
  // One pose attempt. result is cleared first; allocates nothing; bounded work (overflows are
  // counted in the source's own report, never a crash).
  virtual void process(const SourceInput& input, SourceResult& result) = 0;
  // Forgets every earlier frame (tracks, backgrounds, filters): the next process() gives what a
  // source just made would give. Allocates nothing. The default is for a source that keeps nothing
  // from one frame to the next (it reads the last pose from SourceInput::prior).
  virtual void restart() {}
};

}  // namespace irloc
