#include "firmware/strobe_check.hpp"

#include <cstdint>
#include <variant>

namespace irloc::firmware {
namespace {

struct DifferenceCounts {
  std::uint64_t brighter_on = 0;
  std::uint64_t brighter_off = 0;
};

template <typename Pixel>
DifferenceCounts count_differences(const ImageView<Pixel>& on, const ImageView<Pixel>& off, int noise_level) {
  DifferenceCounts counts;
  for (int y = 0; y < on.height(); ++y) {
    const Pixel* on_row = on.row(y);
    const Pixel* off_row = off.row(y);
    for (int x = 0; x < on.width(); ++x) {
      const int difference = static_cast<int>(on_row[x]) - static_cast<int>(off_row[x]);
      counts.brighter_on += difference > noise_level ? 1u : 0u;
      counts.brighter_off += difference < -noise_level ? 1u : 0u;
    }
  }
  return counts;
}

}  // namespace

StrobeVerdict check_strobe_pair(const Frame& on, const Frame& off, const StrobeCheckSettings& settings) {
  if (on.image.index() != off.image.index()) return StrobeVerdict::no_contrast;
  const DifferenceCounts counts = std::visit(
      [&](const auto& on_image) -> DifferenceCounts {
        using View = std::decay_t<decltype(on_image)>;
        const View& off_image = std::get<View>(off.image);
        if (on_image.width() != off_image.width() || on_image.height() != off_image.height()) return {};
        return count_differences(on_image, off_image, settings.noise_level);
      },
      on.image);
  const auto min_pixels = static_cast<std::uint64_t>(settings.min_pixels);
  const auto on_wins = static_cast<double>(counts.brighter_on);
  const auto off_wins = static_cast<double>(counts.brighter_off);
  if (counts.brighter_on >= min_pixels && on_wins >= settings.min_contrast_ratio * off_wins) return StrobeVerdict::verified;
  if (counts.brighter_off >= min_pixels && off_wins >= settings.min_contrast_ratio * on_wins) return StrobeVerdict::swapped;
  return StrobeVerdict::no_contrast;
}

}  // namespace irloc::firmware
