#include "algo/markers/square/square_marker_source.hpp"

#include "algo/core/static_vector.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc {

SquareMarkerSource::SquareMarkerSource(const SourceSetup& setup, const SquareConfig& config)
    : camera_(setup.camera),
      base_from_camera_(setup.base_from_camera),
      dof_(setup.dof),
      detector_(setup.camera, setup.pixel_bits, setup.base_from_camera, setup.dof, setup.map.square_markers, config),
      max_prior_age_ns_(static_cast<std::int64_t>(config.max_prior_age * 1e9)) {}

void SquareMarkerSource::process(const SourceInput& input, SourceResult& result) {
  result.clear(SourceKind::square);
  detection_ = SquareDetection{};
  if (input.off == nullptr) {
    result.outcome = "no LED-off frame";
    return;
  }
  StageClock clock;
  clock.start(result.times);
  // A prior from the frame clock's future (the clock went back) is of unknown age: not used.
  const bool recent = input.prior != nullptr && input.on.t_ns >= input.prior->t_ns &&
                      input.on.t_ns - input.prior->t_ns <= max_prior_age_ns_;
  detection_ = detector_.detect(input.on.image, input.off->image, *input.pair,
                                recent ? &input.prior->world_from_base : nullptr);
  clock.mark(result.times, "square");
  result.outcome = to_string(detection_.outcome).data();  // the names are string literals
  if (!detection_.found()) return;
  result.ok = true;
  result.world_from_base = detection_.world_from_base;
  result.covariance = detection_.covariance;
  result.confidence = detection_.confidence;
  for (std::size_t seen = 0; seen < detection_.square_count; ++seen) {
    const int square = detection_.squares[seen];
    const SquareMarker& marker = detector_.markers()[static_cast<std::size_t>(square)];
    for (int corner = 0; corner < 4; ++corner) {
      const auto k = static_cast<std::size_t>(corner);
      result.observations.push_back({square, corner, detection_.corner_pixels[seen][k], marker.corners[k]});
    }
  }
  if (input.line_time_ns > 0) move_to_frame_time(input, result);
}

// The detector fits lines to the tape points along each side: under a rolling shutter their rows'
// times vary along the side, which the corners alone do not sample. The change the row times make
// is fitted to points spaced along the sides, at the pixels where the found pose sees them.
void SquareMarkerSource::move_to_frame_time(const SourceInput& input, SourceResult& result) const {
  constexpr int kPointsPerSide = 8;
  StaticVector<Eigen::Vector3d, kMaxPointObservations> world;
  StaticVector<Eigen::Vector2d, kMaxPointObservations> pixels;
  const RigidTransform camera_from_world = (result.world_from_base * base_from_camera_).inverse();
  for (std::size_t seen = 0; seen < detection_.square_count; ++seen) {
    const SquareMarker& marker = detector_.markers()[static_cast<std::size_t>(detection_.squares[seen])];
    for (std::size_t side = 0; side < 4; ++side) {
      const Eigen::Vector3d& from = marker.corners[side];
      const Eigen::Vector3d& to = marker.corners[(side + 1) % 4];
      for (int k = 0; k < kPointsPerSide && world.size() < world.capacity(); ++k) {
        const Eigen::Vector3d point = from + (to - from) * (static_cast<double>(k) / kPointsPerSide);
        Eigen::Vector2d pixel;
        if (!camera_.project(camera_from_world * point, pixel)) continue;
        world.push_back(point);
        pixels.push_back(pixel);
      }
    }
  }
  move_fit_to_frame_time(input, camera_, base_from_camera_, dof_, {world.begin(), world.size()},
                         {pixels.begin(), pixels.size()}, result);
}

}  // namespace irloc
