#include "algo/markers/outside_in/appearance_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace irloc::outside_in {
namespace {

constexpr int kBands = AppearanceFitter::kBands;
constexpr int kMaxFaces = AppearanceFitter::kMaxFaces;

// A visible face's (or band's) outline in the image: convex, the projection of a rectangle, the
// lens's bending along its edges neglected.
using FaceQuad = std::array<Eigen::Vector2d, 4>;
using Corners = std::array<Eigen::Vector3d, 4>;  // a face's corners in the box's frame, in order around it
// Per pixel of one row of the region (from its x_min), the face it lies on, -1 for none.
using FaceRow = std::array<std::int8_t, AppearanceFitter::kMaxWidth>;

// The x range of a convex quad's pixel centres on row y, [x_from, x_to] (empty: x_from > x_to).
void row_span(const FaceQuad& quad, double y, double& x_from, double& x_to) {
  x_from = 1e9;
  x_to = -1e9;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d& p = quad[i];
    const Eigen::Vector2d& q = quad[(i + 1) % 4];
    if ((y < p.y() && y < q.y()) || (y > p.y() && y > q.y()) || p.y() == q.y()) continue;
    const double x = p.x() + (q.x() - p.x()) * (y - p.y()) / (q.y() - p.y());
    x_from = std::min(x_from, x);
    x_to = std::max(x_to, x);
  }
}

// The faces the camera sees from `eye` (the camera's centre in the box's frame): the top, and the
// end (end_side +1 at +x, -1 at -x, else 0) and the side whose planes it is in front of.
int faces_seen_from(const Eigen::Vector3d& eye, const BoxBody& body, std::array<Corners, 3>& faces, int& end_side) {
  const double hl = 0.5 * body.length, hw = 0.5 * body.width, h = body.height;
  int count = 0;
  end_side = 0;
  if (eye.z() > h) faces[count++] = {{{hl, hw, h}, {-hl, hw, h}, {-hl, -hw, h}, {hl, -hw, h}}};
  if (eye.x() > hl) {
    faces[count++] = {{{hl, -hw, 0}, {hl, hw, 0}, {hl, hw, h}, {hl, -hw, h}}};
    end_side = 1;
  } else if (eye.x() < -hl) {
    faces[count++] = {{{-hl, -hw, 0}, {-hl, hw, 0}, {-hl, hw, h}, {-hl, -hw, h}}};
    end_side = -1;
  }
  if (eye.z() <= h) end_side = 0;  // an end's shades are over the top's: none without it
  if (eye.y() > hw) faces[count++] = {{{-hl, hw, 0}, {hl, hw, 0}, {hl, hw, h}, {-hl, hw, h}}};
  else if (eye.y() < -hw) faces[count++] = {{{-hl, -hw, 0}, {hl, -hw, 0}, {hl, -hw, h}, {-hl, -hw, h}}};
  return count;
}

// The visible faces at `pose`, each side cut into kBands bands of its height, projected; -1 when a
// corner is behind the camera or outside the lens's range. end_side: faces_seen_from's.
int visible_faces(const BoxSilhouette& box, const FloorPose& pose, std::array<FaceQuad, kMaxFaces>& quads, int& end_side) {
  const BoxBody& body = box.body();
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  const Eigen::Vector3d offset = box.camera_from_world().inverse().translation - Eigen::Vector3d(pose.x, pose.y, 0);
  const Eigen::Vector3d eye(c * offset.x() + s * offset.y(), -s * offset.x() + c * offset.y(), offset.z());
  std::array<Corners, 3> faces;
  const int face_count = faces_seen_from(eye, body, faces, end_side);
  std::array<Corners, kMaxFaces> parts;
  int count = 0;
  for (int f = 0; f < face_count; ++f) {
    const Corners& face = faces[static_cast<std::size_t>(f)];
    if (face[0].z() > 0) {  // the top
      parts[static_cast<std::size_t>(count++)] = face;
      continue;
    }
    for (int band = 0; band < kBands; ++band) {
      Corners part = face;
      part[0].z() = part[1].z() = body.height * band / kBands;
      part[2].z() = part[3].z() = body.height * (band + 1) / kBands;
      parts[static_cast<std::size_t>(count++)] = part;
    }
  }
  for (std::size_t f = 0; f < static_cast<std::size_t>(count); ++f)
    for (std::size_t i = 0; i < 4; ++i) {
      const Eigen::Vector3d& b = parts[f][i];
      const Eigen::Vector3d world(pose.x + c * b.x() - s * b.y(), pose.y + s * b.x() + c * b.y(), b.z());
      const Eigen::Vector3d point_c = box.camera_from_world() * world;
      if (point_c.z() <= 0 || !box.camera().project(point_c, quads[f][i])) return -1;
    }
  return count;
}

// The faces on row y of [x_from, x_to]: where faces overlap in the image, the first of them (the
// top before the sides).
void faces_on_row(const std::array<FaceQuad, kMaxFaces>& quads, int count, int y, int x_from, int x_to, FaceRow& row) {
  std::fill(row.begin(), row.begin() + (x_to - x_from + 1), std::int8_t{-1});
  for (int f = count - 1; f >= 0; --f) {
    double from = 0, to = 0;
    row_span(quads[static_cast<std::size_t>(f)], y, from, to);
    const int first = std::max(x_from, static_cast<int>(std::ceil(std::clamp(from, -1e6, 1e6))));
    const int last = std::min(x_to, static_cast<int>(std::floor(std::clamp(to, -1e6, 1e6))));
    for (int x = first; x <= last; ++x) row[static_cast<std::size_t>(x - x_from)] = static_cast<std::int8_t>(f);
  }
}

}  // namespace

AppearanceFitter::AppearanceFitter(const BoxSilhouette& box, int width, int height)
    : box_(box), width_(width), height_(height) {
  if (width < 1 || width > kMaxWidth || height < 1)
    throw std::invalid_argument("appearance fit: image width " + std::to_string(width) + " outside 1.." +
                                std::to_string(kMaxWidth));
}

AppearanceFitter::Cost AppearanceFitter::cost(ImageView8 frame, const AdaptiveBackground& background, const Region& region,
                                              const FloorPose& pose, double give_up_above) const {
  Cost result;
  std::array<FaceQuad, kMaxFaces> quads;
  const int count = visible_faces(box_, pose, quads, result.end_side);
  if (count <= 0) return result;
  // Two passes over the region: each face's shade (the mean it covers), then the residuals.
  std::array<double, kMaxFaces> sum{};
  std::array<double, kMaxFaces>& shade = result.shade;
  std::array<int, kMaxFaces>& covered = result.covered;
  FaceRow faces;
  for (int y = region.y_min; y <= region.y_max; y += region.step) {
    faces_on_row(quads, count, y, region.x_min, region.x_max, faces);
    const std::uint8_t* row = frame.row(y);
    for (int x = region.x_min; x <= region.x_max; x += region.step) {
      const int f = faces[static_cast<std::size_t>(x - region.x_min)];
      if (f < 0) continue;
      sum[static_cast<std::size_t>(f)] += row[x];
      ++covered[static_cast<std::size_t>(f)];
    }
  }
  for (std::size_t f = 0; f < static_cast<std::size_t>(count); ++f) shade[f] = covered[f] ? sum[f] / covered[f] : 0;
  constexpr double kCap = kTruncation * kTruncation;
  for (int y = region.y_min; y <= region.y_max; y += region.step) {
    faces_on_row(quads, count, y, region.x_min, region.x_max, faces);
    const std::uint8_t* row = frame.row(y);
    for (int x = region.x_min; x <= region.x_max; x += region.step) {
      const int f = faces[static_cast<std::size_t>(x - region.x_min)];
      const double floor = background.value_q8_8_at(x, y) / 256.0;
      const double expected = f < 0 ? floor : shade[static_cast<std::size_t>(f)];
      const double r2 = (row[x] - expected) * (row[x] - expected);
      result.value += std::min(r2, kCap);
      result.outliers += r2 > kCap;
      ++result.samples;
      if (f < 0) continue;
      ++result.box_samples;
      result.box_outliers += r2 > kCap;
      result.contrasted += std::abs(expected - floor) > kTruncation;
    }
    if (result.value > give_up_above) return result;
  }
  result.ok = result.box_samples > 0;
  return result;
}

EndView AppearanceFitter::Cost::end_view() const {
  EndView view;
  if (end_side == 0 || covered[0] < EndView::kMinBandSamples || shade[0] <= 0 ||
      box_outliers > EndView::kMaxBoxOutliers * box_samples)
    return view;
  for (std::size_t band = 0; band < static_cast<std::size_t>(kBands); ++band) {
    if (covered[1 + band] < EndView::kMinBandSamples) return view;
    view.ratio[band] = shade[1 + band] / shade[0];
  }
  view.side = end_side;
  return view;
}

AppearanceFitter::Cost AppearanceFitter::descend(ImageView8 frame, const AdaptiveBackground& background,
                                                 const Region& region, FloorPose& pose, int& evaluations) const {
  Cost best = cost(frame, background, region, pose, std::numeric_limits<double>::infinity());
  int used = 1;
  double step_m = kFirstStepM, step_rad = kFirstStepRad;
  for (int level = 0; best.ok && level < kLevels; ++level, step_m *= 0.5, step_rad *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      const std::array<FloorPose, 6> moves{{{step_m, 0, 0}, {-step_m, 0, 0}, {0, step_m, 0},
                                            {0, -step_m, 0}, {0, 0, step_rad}, {0, 0, -step_rad}}};
      for (const FloorPose& move : moves) {
        if (used >= kMaxEvaluations) break;
        const FloorPose candidate{pose.x + move.x, pose.y + move.y, pose.yaw + move.yaw};
        const Cost c = cost(frame, background, region, candidate, best.value);
        ++used;
        if (c.ok && c.value < best.value) best = c, pose = candidate, improved = true;
      }
    }
  }
  evaluations += used;
  return best;
}

AppearanceFit AppearanceFitter::refine(ImageView8 frame, const AdaptiveBackground& background,
                                       std::span<const FloorPose> starts) const {
  if (starts.size() > static_cast<std::size_t>(kMaxStarts))
    throw std::invalid_argument("appearance fit: " + std::to_string(starts.size()) + " starts, at most " +
                                std::to_string(kMaxStarts));
  AppearanceFit fit;
  Region region{width_, height_, -1, -1};
  for (const FloorPose& start : starts) {
    Silhouette outline;
    if (!box_.project(start, outline)) continue;  // its descent's first cost is not ok either
    region.x_min = std::min(region.x_min, std::max(0, outline.x_min - kMarginPx));
    region.y_min = std::min(region.y_min, std::max(0, outline.y_min - kMarginPx));
    region.x_max = std::max(region.x_max, std::min(width_ - 1, outline.x_max + kMarginPx));
    region.y_max = std::max(region.y_max, std::min(height_ - 1, outline.y_max + kMarginPx));
  }
  if (region.x_max < region.x_min || region.y_max < region.y_min) return fit;
  const long pixels = static_cast<long>(region.x_max - region.x_min + 1) * (region.y_max - region.y_min + 1);
  while (pixels > static_cast<long>(kMaxSamples) * region.step * region.step) ++region.step;

  Cost best;
  for (const FloorPose& start : starts) {
    FloorPose pose = start;
    const Cost ended = descend(frame, background, region, pose, fit.evaluations);
    if (!ended.ok || (best.ok && ended.value >= best.value)) continue;
    best = ended;
    fit.pose = pose;
  }
  if (!best.ok) return fit;
  fit.ok = true;
  fit.box_outlier_fraction = static_cast<double>(best.box_outliers) / best.box_samples;
  fit.around_outlier_fraction =
      static_cast<double>(best.outliers - best.box_outliers) / std::max(1, best.samples - best.box_samples);
  fit.contrast_fraction = static_cast<double>(best.contrasted) / best.box_samples;
  fit.end = best.end_view();
  return fit;
}

}  // namespace irloc::outside_in
