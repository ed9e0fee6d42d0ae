#include "firmware/calibration_run.hpp"

#include <cstdio>
#include <system_error>

#include <yaml-cpp/yaml.h>

#include "algo/calibration/drive_calibration.hpp"
#include "firmware/calibration_report.hpp"
#include "io/config/camera_info_writer.hpp"
#include "io/files/output_file.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

YAML::Node flow_sequence(std::initializer_list<double> values) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (const double value : values) node.push_back(value);
  return node;
}

// The input config with the refined mount, the calibration beside it and the map by absolute path.
std::string refined_config(const std::filesystem::path& config_file, const std::filesystem::path& map_file,
                           const RigidTransform& mount) {
  YAML::Node root = YAML::LoadFile(config_file.string());
  root["camera"]["calibration"] = "calib.yaml";
  const Eigen::Matrix3d& r = mount.rotation;
  const Eigen::Vector3d& t = mount.translation;
  YAML::Node node(YAML::NodeType::Map);
  node["rotation"] = flow_sequence({r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)});
  node["xyz"] = flow_sequence({t.x(), t.y(), t.z()});
  root["camera"]["mount"] = node;
  root["map"] = std::filesystem::absolute(map_file).lexically_normal().string();
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << root;
  return "# Written by irlocd --calibrate from " + config_file.string() + "\n" + emitter.c_str() + "\n";
}

std::string residuals_csv(const calibration::CalibrationResult& result) {
  std::string text = "u,v,before_du,before_dv,after_du,after_dv\n";
  char line[160];
  for (const calibration::DotResidual& r : result.residuals) {
    std::snprintf(line, sizeof line, "%.3f,%.3f,%.4f,%.4f,%.4f,%.4f\n", r.pixel.x(), r.pixel.y(), r.before.x(),
                  r.before.y(), r.after.x(), r.after.y());
    text += line;
  }
  return text;
}

}  // namespace

CalibrationRun::CalibrationRun(std::filesystem::path out_dir, std::filesystem::path config_file,
                               std::filesystem::path map_file, const Localizer& localizer)
    : out_dir_(std::move(out_dir)), config_file_(std::move(config_file)), map_file_(std::move(map_file)),
      localizer_(localizer) {
  if (localizer.setup().map.dot_markers.empty()) {
    throw io::InputError("--calibrate: the map " + map_file_.string() + " has no dot markers to calibrate from");
  }
}

void CalibrationRun::on_attempt(const StrobePair& pair, std::optional<StrobeVerdict>, bool computed, const PoseEstimate&) {
  if (!computed) return;
  for (const SourceResult& result : localizer_.last_results()) add(pair.on.t_ns, result);
}

void CalibrationRun::add(std::int64_t t_ns, const SourceResult& result) {
  // Also the poses refused only for their confidence: they carry the dots their fit used, and a
  // wrong calibration is what lowers the confidence of the fit (its reprojection error).
  if (result.kind != SourceKind::dot || result.observations.empty() || !result.at_frame_time()) return;
  drive_.add(t_ns, result.world_from_base,
             std::span<const PointObservation>(result.observations.begin(), result.observations.end()));
}

std::string CalibrationRun::finish() const {
  const LocalizerSetup& setup = localizer_.setup();
  calibration::CalibrationOptions options;
  options.dof = setup.dof;
  const calibration::CalibrationResult result = calibration::calibrate_from_drive(drive_, setup.camera, setup.mount, options);
  if (!result.ok) throw io::InputError("--calibrate: no calibration from this drive: " + result.message);
  std::error_code error;
  std::filesystem::create_directories(out_dir_, error);
  if (error) throw io::InputError("--calibrate " + out_dir_.string() + ": cannot create the folder: " + error.message());
  const auto write = [&](const char* name, const std::string& text) {
    io::replace_file_atomically(out_dir_ / name, text, 0644, "the calibration output");
  };
  write("calib.yaml",
        io::camera_info_yaml(result.camera, "irloc_calibrated", "Written by irlocd --calibrate (self-calibration from the ceiling)."));
  write("config.yaml", refined_config(config_file_, map_file_, result.mount));
  write("calibration_report.txt", calibration_report(result, drive_.frames_dropped(), config_file_.string()));
  write("residuals.csv", residuals_csv(result));
  char summary[256];
  std::snprintf(summary, sizeof summary, "calibrated from %zu poses: dot residual RMS %.3f -> %.3f px; written to %s",
                result.poses.size(), result.before.rms_px, result.after.rms_px, out_dir_.string().c_str());
  return summary;
}

}  // namespace irloc::firmware
