#include "firmware/front_end_probe.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string_view>
#include <variant>

namespace irloc::firmware {
namespace {

// Copies the frame's rows to dest (one memcpy when they are contiguous); returns the bytes copied.
template <typename Pixel>
std::size_t copy_frame(ImageView<const Pixel> image, std::byte* dest) {
  const std::size_t row_bytes = static_cast<std::size_t>(image.width()) * sizeof(Pixel);
  if (image.stride() == image.width()) {
    std::memcpy(dest, image.data(), row_bytes * static_cast<std::size_t>(image.height()));
  } else {
    for (int y = 0; y < image.height(); ++y) std::memcpy(dest + static_cast<std::size_t>(y) * row_bytes, image.row(y), row_bytes);
  }
  return row_bytes * static_cast<std::size_t>(image.height());
}

std::size_t bytes_of(const GrayImageView& image) {
  const std::size_t pixel = std::holds_alternative<ImageView8>(image) ? 1 : 2;
  return static_cast<std::size_t>(width_of(image)) * static_cast<std::size_t>(height_of(image)) * pixel;
}

template <std::size_t N>
double median_of(std::array<double, N> values, std::size_t count) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(values.begin(), middle, values.begin() + static_cast<std::ptrdiff_t>(count));
  return *middle;
}

}  // namespace

double front_end_total_ms(const StageClock::Times& times) {
  double total = 0;
  for (const StageTime& stage : times) {
    if (std::string_view(stage.name) == "front_end") total += stage.milliseconds;
  }
  return total;
}

FrontEndProbe::FrontEndProbe(int width, int height)
    : copy_(2 * static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0)) * 2) {}

void FrontEndProbe::after_attempt(const StrobePair& pair, const StageClock::Times& times) {
  if (!pair.off || attempts_++ % kEvery != 0) return;
  // A pair the Localizer refused (another size or depth) has no front end to compare.
  const bool ran = std::any_of(times.begin(), times.end(), [](const StageTime& s) { return std::string_view(s.name) == "front_end"; });
  if (!ran || bytes_of(pair.on.image) + bytes_of(pair.off->image) > copy_.size()) return;
  const double front_end_ms = front_end_total_ms(times);
  const auto start = std::chrono::steady_clock::now();
  std::visit(
      [&](const auto& on) {
        const auto& off = std::get<std::decay_t<decltype(on)>>(pair.off->image);
        copy_frame(off, copy_.data() + copy_frame(on, copy_.data()));
      },
      pair.on.image);
  const double memcpy_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const std::size_t slot = static_cast<std::size_t>(samples_++ % kSamples);
  front_end_ms_[slot] = front_end_ms;
  memcpy_ms_[slot] = memcpy_ms;
}

std::optional<FrontEndVsMemcpy> FrontEndProbe::summary() const {
  if (samples_ == 0) return std::nullopt;
  const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(samples_, kSamples));
  FrontEndVsMemcpy summary;
  summary.samples = samples_;
  summary.front_end_ms = median_of(front_end_ms_, count);
  summary.memcpy_pair_ms = median_of(memcpy_ms_, count);
  summary.ratio = summary.memcpy_pair_ms > 0 ? summary.front_end_ms / summary.memcpy_pair_ms : 0;
  return summary;
}

}  // namespace irloc::firmware
