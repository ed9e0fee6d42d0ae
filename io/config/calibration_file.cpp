#include "io/config/calibration_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/config/yaml_reader.hpp"

namespace irloc::io {
namespace {

// Ranges of docs/formats.md. The pixel count bounds every per-pixel table built from the
// calibration (64 Mpixel: 256 MiB of 4-byte entries).
constexpr long long kMaxImageSide = 16384;
constexpr long long kMaxImagePixels = 1LL << 26;
constexpr double kMinFocalPx = 1;
constexpr double kMaxFocalPx = 100'000;
constexpr double kMaxDistortion = 100;
constexpr Range kAnyFinite{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::max()};

// A camera_info matrix: {rows: R, cols: C, data: [R*C numbers]}, or an OpenCV one (tagged
// !!opencv-matrix, with dt: d or f; vectors written as N x 1).
std::vector<double> read_matrix(YamlMap& parent, const std::string& key, int rows, int cols_min, int cols_max,
                                Range range) {
  YamlMap matrix = parent.map(key);
  long long r = matrix.integer("rows", 0, 16);
  long long c = matrix.integer("cols", 0, 16);
  if (matrix.has("dt")) {
    const std::string type = matrix.text("dt");
    if (type != "d" && type != "f") matrix.fail_key("dt", "expected d or f (a matrix of reals), got '" + type + "'");
    if (rows == 1 && c == 1 && r > 1) std::swap(r, c);
  }
  if (r != rows || c < cols_min || c > cols_max) {
    const std::string cols = cols_min == cols_max ? std::to_string(cols_min)
                                                  : std::to_string(cols_min) + ".." + std::to_string(cols_max);
    matrix.fail("expected rows: " + std::to_string(rows) + " and cols: " + cols + ", got " +
                std::to_string(r) + " x " + std::to_string(c));
  }
  std::vector<double> data = matrix.numbers("data", static_cast<std::size_t>(r * c), range);
  matrix.reject_unknown_keys();
  return data;
}

}  // namespace

CameraIntrinsics load_camera_info(const std::filesystem::path& path) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  return read_camera_info(root);
}

namespace {

void read_image_size(YamlMap& root, CameraIntrinsics& camera) {
  const long long width = root.integer("image_width", 1, kMaxImageSide);
  const long long height = root.integer("image_height", 1, kMaxImageSide);
  if (width * height > kMaxImagePixels) {
    root.fail_key("image_height", "image_width x image_height must be at most " + std::to_string(kMaxImagePixels) +
                                      " pixels, got " + std::to_string(width * height));
  }
  camera.width = static_cast<int>(width);
  camera.height = static_cast<int>(height);
}

// [fx, 0, cx, 0, fy, cy, 0, 0, 1], each entry in its range; the image size read before.
void read_camera_matrix(YamlMap& root, CameraIntrinsics& camera) {
  const std::vector<double> k = read_matrix(root, "camera_matrix", 3, 3, 3, kAnyFinite);  // each entry checked below
  if (k[1] != 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1) {
    root.fail_key("camera_matrix", "expected [fx, 0, cx, 0, fy, cy, 0, 0, 1]");
  }
  const auto check = [&](double value, const char* name, double low, double high) {
    if (!(value >= low && value <= high)) {
      root.fail_key("camera_matrix", std::string(name) + ": must be in " + range_text(low, high) + ", got " +
                                         number_text(value));
    }
  };
  check(k[0], "fx", kMinFocalPx, kMaxFocalPx);
  check(k[4], "fy", kMinFocalPx, kMaxFocalPx);
  // The principal point lies within a few image widths (heights) of the image: a small window of
  // a larger sensor (the simulator renders such crops) may put it outside, a lens centred farther
  // away is a wrong file.
  check(k[2], "cx", -4.0 * camera.width, 5.0 * camera.width);
  check(k[5], "cy", -4.0 * camera.height, 5.0 * camera.height);
  camera.fx = k[0];
  camera.cx = k[2];
  camera.fy = k[4];
  camera.cy = k[5];
}

// The lens model and its coefficients: camera_info's distortion_model, or for OpenCV's file its
// fisheye_model flag.
void read_distortion(YamlMap& root, bool opencv_file, CameraIntrinsics& camera) {
  std::string model;
  if (opencv_file) {
    // cv::calibrateCamera (pinhole) unless the file says it came from cv::fisheye::calibrate.
    const long long fisheye = root.integer("fisheye_model", 0, 1, 0);
    model = fisheye == 1 ? "equidistant" : "plumb_bob";
  } else {
    model = root.text("distortion_model");
  }
  int coefficients = 0;
  if (model == "plumb_bob") {
    camera.model = LensModel::plumb_bob;
    coefficients = 5;
  } else if (model == "equidistant") {
    camera.model = LensModel::equidistant;
    coefficients = 4;
  } else if (model == "equisolid") {
    camera.model = LensModel::equisolid;
  } else {
    root.fail_key("distortion_model",
              "unknown model '" + model + "' (expected plumb_bob, equidistant or equisolid)");
  }
  // plumb_bob may give 4 (k3 = 0) or 5; equisolid none, or zeros.
  const int cols_min = camera.model == LensModel::plumb_bob ? 4 : coefficients;
  const int cols_max = camera.model == LensModel::equisolid ? 5 : coefficients;
  const std::vector<double> d = read_matrix(root, "distortion_coefficients", 1, cols_min, cols_max,
                                            {-kMaxDistortion, kMaxDistortion});
  if (camera.model == LensModel::equisolid) {
    if (std::any_of(d.begin(), d.end(), [](double x) { return x != 0; })) {
      root.fail_key("distortion_coefficients", "the equisolid model takes no coefficients (empty or all zero)");
    }
  } else {
    std::copy(d.begin(), d.end(), camera.distortion.begin());
  }
}

}  // namespace

CameraIntrinsics read_camera_info(YamlMap& root) {
  CameraIntrinsics camera;
  // The file of OpenCV's calibration tools: no distortion_model, matrices with a dt key.
  const bool opencv_file =
      !root.has("distortion_model") && root.has("camera_matrix") && YamlMap(root).map("camera_matrix").has("dt");
  read_image_size(root, camera);
  read_camera_matrix(root, camera);
  read_distortion(root, opencv_file, camera);
  // Keys of camera_info that irloc has no use for.
  for (const char* key : {"camera_name", "rectification_matrix", "projection_matrix", "binning_x", "binning_y", "roi", "header"}) {
    root.ignore(key);
  }
  if (opencv_file) {  // and those OpenCV's calibration sample and tutorial write
    for (const char* key : {"calibration_time", "nframes", "nr_of_frames", "board_width", "board_height",
                            "square_size", "aspectRatio", "fix_aspect_ratio", "flags", "avg_reprojection_error",
                            "per_view_reprojection_errors", "extrinsic_parameters", "image_points", "grid_points"}) {
      root.ignore(key);
    }
  }
  root.reject_unknown_keys();
  return camera;
}

}  // namespace irloc::io
