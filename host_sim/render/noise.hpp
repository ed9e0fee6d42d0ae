#pragma once
// The image sensor: scene radiance to digital numbers with shot noise, read noise, black level,
// saturation and quantisation to 8, 10 or 12 bits. Deterministic: the noise of pixel row y of
// frame seq depends only on (seed, seq, y), so any split of rows over threads gives the same image.

#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// A small, fast, seedable generator (splitmix64) with standard normal draws (Box-Muller).
class NoiseSource {
 public:
  explicit NoiseSource(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform();  // in [0, 1)
  double normal();   // mean 0, standard deviation 1

 private:
  std::uint64_t state_;
  double spare_ = 0;
  bool has_spare_ = false;
};

// A well-mixed seed for stream `a`, item `b` of run `seed`.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b);

class Sensor {
 public:
  Sensor(const CameraSpec& camera, std::uint64_t seed);

  int max_value() const { return max_value_; }

  // Mean electrons of a pixel looking at `radiance` (W sr^-1 m^-2) for one exposure.
  double electrons(double radiance) const { return radiance * electrons_per_radiance_; }

  // Converts row y of frame `seq` (radiance per pixel) to digital numbers.
  template <typename Pixel>
  void expose_row(std::span<const float> radiance, std::uint64_t seq, int y, Pixel* out) const;

 private:
  CameraSpec camera_;
  std::uint64_t seed_;
  int max_value_;
  double electrons_per_radiance_;
};

}  // namespace irloc::sim
