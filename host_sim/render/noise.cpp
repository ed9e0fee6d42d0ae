#include "host_sim/render/noise.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irloc::sim {

std::uint64_t NoiseSource::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double NoiseSource::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double NoiseSource::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
  const double u2 = uniform();
  const double radius = std::sqrt(-2 * std::log(u1));
  spare_ = radius * std::sin(2 * std::numbers::pi * u2);
  has_spare_ = true;
  return radius * std::cos(2 * std::numbers::pi * u2);
}

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  NoiseSource mixer(seed ^ (a * 0xD1B54A32D192ED03ull) ^ (b * 0x8CB92BA72F3D8DD7ull));
  mixer.next();
  return mixer.next();
}

Sensor::Sensor(const CameraSpec& camera, std::uint64_t seed)
    : camera_(camera),
      seed_(seed),
      max_value_((1 << camera.bit_depth) - 1),
      electrons_per_radiance_(camera.sensitivity * camera.exposure * camera.full_well) {}

template <typename Pixel>
void Sensor::expose_row(std::span<const float> radiance, std::uint64_t seq, int y, Pixel* out) const {
  NoiseSource noise(mix_seed(seed_, seq, static_cast<std::uint64_t>(y)));
  const double black = camera_.black_level * camera_.full_well;
  const double scale = max_value_ / camera_.full_well;
  for (std::size_t x = 0; x < radiance.size(); ++x) {
    double signal = electrons(radiance[x]);
    if (camera_.noise) {
      signal += std::sqrt(signal) * noise.normal() + camera_.read_noise * noise.normal();
    }
    const double value = std::round((black + signal) * scale);
    out[x] = static_cast<Pixel>(std::clamp(value, 0.0, static_cast<double>(max_value_)));
  }
}

template void Sensor::expose_row<std::uint8_t>(std::span<const float>, std::uint64_t, int, std::uint8_t*) const;
template void Sensor::expose_row<std::uint16_t>(std::span<const float>, std::uint64_t, int, std::uint16_t*) const;

}  // namespace irloc::sim
