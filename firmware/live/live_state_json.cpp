#include "firmware/live/live_state_json.hpp"

#include <cmath>
#include <string>

#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::firmware {
namespace {

using nlohmann::json;

json pose_json(const PoseEstimate& e) {
  json pose = {{"ok", e.ok}, {"seq", e.seq}, {"t_ns", e.t_ns}};
  if (!e.ok) return pose;
  pose.update({{"source", std::string(to_string(e.source))},
               {"x", e.x}, {"y", e.y}, {"z", e.z}, {"roll", e.roll}, {"pitch", e.pitch}, {"yaw", e.yaw},
               {"marker_id", e.marker_id}, {"confidence", e.confidence}});
  // One-sigma of each parameter (m, rad) and the whole covariance, row-major.
  json sigma = json::object(), covariance = json::array();
  const char* names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (int i = 0; i < 6; ++i) {
    sigma[names[i]] = std::sqrt(std::max(0.0, e.covariance(i, i)));
    for (int j = 0; j < 6; ++j) covariance.push_back(e.covariance(i, j));
  }
  pose["sigma"] = sigma;
  pose["covariance"] = covariance;
  return pose;
}

json warnings_json(const LiveSnapshot& s) {
  json warnings = json::array();
  const auto warn = [&](std::string text) { warnings.push_back(std::move(text)); };
  if (s.verdict == StrobeVerdict::swapped) warn("strobe out of step: this pair's LED-off frame was the brighter one");
  if (s.verdict == StrobeVerdict::no_contrast) warn("no strobe contrast: LEDs off or dead, lens covered, or nothing in view");
  if (s.strobe && s.strobe->resyncs > 0) warn(std::to_string(s.strobe->resyncs) + " strobe resyncs since start");
  if (s.loop.dropped_frames > 0) warn(std::to_string(s.loop.dropped_frames) + " dropped frames since start");
  if (s.loop.outputs_failed > 0) warn("an output (--record, --pose-csv) stopped: a write failed, see the log");
  if (s.bad_frames > 0) warn(std::to_string(s.bad_frames) + " pairs of the wrong size or depth refused");
  if (s.blobs_dropped > 0) warn(std::to_string(s.blobs_dropped) + " blobs beyond capacity dropped: too many bright spots");
  for (const LiveSourceAttempt& source : s.sources) {
    if (source.observations.dropped() > 0) {
      warn(std::string(to_string(source.kind)) + ": " + std::to_string(source.observations.dropped()) +
           " measured points beyond capacity dropped");
    }
  }
  if (s.stream_ended) warn("the recording has ended: this is its last pose attempt");
  return warnings;
}

}  // namespace

json live_state_json(const LiveSnapshot& s) {
  json state = {{"publication", s.publication}, {"image", {{"width", s.width}, {"height", s.height}, {"has_off", s.has_off}}}};
  state["pose"] = pose_json(s.estimate);
  state["computed"] = s.computed;
  json sources = json::array();
  for (const LiveSourceAttempt& source : s.sources) {
    sources.push_back({{"kind", std::string(to_string(source.kind))}, {"ok", source.ok}, {"outcome", source.outcome},
                       {"marker_id", source.marker_id}, {"confidence", source.confidence}, {"rms_px", source.rms_px},
                       {"points", source.observations.size()}});
  }
  state["sources"] = sources;
  state["blobs"] = s.blobs.size();
  json strobe = {{"verdict", s.verdict ? json(strobe_verdict_name(*s.verdict)) : json(nullptr)}};
  if (s.strobe) {
    strobe.update({{"verified", s.strobe->verified}, {"swapped", s.strobe->swapped}, {"no_contrast", s.strobe->no_contrast},
                   {"resyncs", s.strobe->resyncs}});
  }
  state["strobe"] = strobe;
  state["frames_per_second"] = s.frames_per_second;
  state["counters"] = {{"frames", s.loop.frames}, {"dropped_frames", s.loop.dropped_frames},
                       {"pose_attempts", s.loop.pose_attempts}, {"poses_ok", s.loop.poses_ok}, {"unpaired", s.loop.unpaired},
                       {"strobe_rejected", s.loop.strobe_rejected}, {"outputs_failed", s.loop.outputs_failed},
                       {"bad_frames", s.bad_frames}};
  json stages = json::array();
  double latency_ms = 0;
  for (const StageTime& stage : s.stage_times) {
    stages.push_back({{"name", stage.name}, {"ms", stage.milliseconds}});
    latency_ms += stage.milliseconds;
  }
  state["stages_ms"] = stages;
  state["latency_ms"] = latency_ms;  // the pose attempt's own time: the sum of its stages
  json track = json::array();
  for (const LiveTrackPoint& point : s.track) track.push_back({point.x, point.y});
  state["track"] = track;
  state["warnings"] = warnings_json(s);
  state["stream_ended"] = s.stream_ended;
  return state;
}

json live_map_json(const MarkerMap& map) {
  json dots = json::array(), squares = json::array(), leds = json::array();
  for (const DotMarker& marker : map.dot_markers) {
    const Eigen::Vector3d centre = dot::cell_in_world(marker, dot::cell_index(1, 1)) / 2 +
                                   dot::cell_in_world(marker, dot::cell_index(2, 2)) / 2;
    dots.push_back({{"id", marker.id}, {"x", centre.x()}, {"y", centre.y()}});
  }
  for (const SquareMarker& square : map.square_markers) {
    json corners = json::array();
    for (const Eigen::Vector3d& corner : square.corners) corners.push_back({corner.x(), corner.y()});
    squares.push_back({{"name", square.name}, {"corners", corners}});
  }
  for (const LedLandmark& led : map.led_landmarks) leds.push_back({{"name", led.name}, {"x", led.position.x()}, {"y", led.position.y()}});
  return {{"dot_markers", dots}, {"square_markers", squares}, {"led_landmarks", leds}};
}

}  // namespace irloc::firmware
