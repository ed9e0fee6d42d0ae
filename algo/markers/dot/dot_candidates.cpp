#include "algo/markers/dot/dot_candidates.hpp"

#include <algorithm>
#include <variant>

namespace irloc::dot {
namespace {

// Blobs smaller than this are too coarse for a meaningful elongation.
constexpr std::uint32_t kMinAreaForShapeTest = 6;

// Mean grey level of the 3 x 3 pixels around (x, y), clipped to the image.
template <typename Pixel>
double local_mean(ImageView<const Pixel> image, int x, int y) {
  std::uint32_t sum = 0;
  int count = 0;
  for (int yy = std::max(0, y - 1); yy <= std::min(image.height() - 1, y + 1); ++yy) {
    for (int xx = std::max(0, x - 1); xx <= std::min(image.width() - 1, x + 1); ++xx) {
      sum += image.at(xx, yy);
      ++count;
    }
  }
  return count > 0 ? static_cast<double>(sum) / count : 0.0;
}

}  // namespace

DotCandidateSelector::DotCandidateSelector(const DotSourceConfig& config, const CameraModel& camera,
                                           const NominalPlane& plane, double expected_area)
    : config_(config), camera_(camera), plane_(plane), max_area_(config.max_area_factor * expected_area + 9.0) {}

CandidateCounters DotCandidateSelector::select(const BlobList& blobs, const GrayImageView& off,
                                               DotCandidateList& candidates) const {
  candidates.clear();
  CandidateCounters counters;
  counters.blobs = static_cast<std::uint32_t>(blobs.size());
  for (const Blob& blob : blobs) {
    if (blob.area < config_.min_area || static_cast<double>(blob.area) > max_area_) {
      ++counters.wrong_size;
      continue;
    }
    if (blob.area >= kMinAreaForShapeTest && blob.elongation() > config_.max_elongation) {
      ++counters.not_round;
      continue;
    }
    DotCandidate candidate;
    candidate.pixel = {blob.centroid_x(), blob.centroid_y()};
    candidate.area = blob.area;
    candidate.mean_intensity = blob.mean_intensity();
    const int x = static_cast<int>(candidate.pixel.x() + 0.5);
    const int y = static_cast<int>(candidate.pixel.y() + 0.5);
    const double off_level = std::visit([&](const auto& view) { return local_mean(view, x, y); }, off);
    const double contrast = candidate.mean_intensity / (candidate.mean_intensity + off_level);
    if (contrast < config_.min_contrast) {
      ++counters.low_contrast;
      continue;
    }
    if (!camera_.unproject(candidate.pixel, candidate.bearing) || !plane_.intersect(candidate.bearing, candidate.plane)) {
      ++counters.off_ray;
      continue;
    }
    candidates.push_back(candidate);
  }
  counters.dropped = candidates.dropped();
  return counters;
}

}  // namespace irloc::dot
