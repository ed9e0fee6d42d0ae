#include "host_sim/render/renderer.hpp"

#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>

#include "host_sim/render/cylinder_hit.hpp"
#include "host_sim/render/landmark_spots.hpp"
#include "host_sim/render/radiometry.hpp"

namespace irloc::sim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kInvPi = 1 / std::numbers::pi;

}  // namespace

// Everything about one exposure instant that all rays share.
struct Renderer::Instant {
  Eigen::Isometry3d t_w_c;
  bool led_on;
  RingIllumination ring;
  std::vector<Eigen::Vector2d> people;  // positions
  std::vector<double> landmark_radiance;  // emitter radiance toward the camera
};

// Smooth shading terms, computed once per pixel for the first ray that needs them.
struct Renderer::PixelCache {
  double ceiling = -1, wall = -1, person = -1, retro = -1;
  bool ceiling_seen = false;
  bool ceiling_empty = false;      // nothing on the ceiling within a grid cell of `anchor`
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();
};

void for_each_row(int rows, const std::function<void(int)>& body) {
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<int> next{0};
  const auto worker = [&] {
    for (int row = next++; row < rows; row = next++) body(row);
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
}

Renderer::Renderer(const Scenario& scenario, const CameraModel& camera)
    : scenario_(scenario),
      camera_(camera),
      trajectory_(scenario.trajectory),
      ceiling_(scenario.map, scenario.room),
      width_(camera.intrinsics().width),
      height_(camera.intrinsics().height),
      samples_per_pixel_(scenario.supersampling * scenario.supersampling) {
  const int n = scenario.supersampling;
  const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  bearings_.resize(pixels * static_cast<std::size_t>(samples_per_pixel_));
  centres_.resize(pixels);
  spreads_.resize(pixels);
  for_each_row(height_, [&](int y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
      Eigen::Vector3f* out = &bearings_[pixel * static_cast<std::size_t>(samples_per_pixel_)];
      Eigen::Vector3d centre;
      const bool centre_valid = camera_.unproject(Eigen::Vector2d(x, y), centre);
      centres_[pixel] = centre.cast<float>();
      double spread = centre_valid ? 0 : -1;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const Eigen::Vector2d sub_pixel(x + (j + 0.5) / n - 0.5, y + (i + 0.5) / n - 0.5);
          Eigen::Vector3d bearing;
          if (camera_.unproject(sub_pixel, bearing)) {
            *out++ = bearing.cast<float>();
            if (spread >= 0) spread = std::max(spread, std::acos(std::min(1.0, bearing.dot(centre))));
          } else {
            *out++ = Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0, 0);
            spread = -1;
          }
        }
      }
      spreads_[pixel] = static_cast<float>(spread);
    }
  });
}

Eigen::Isometry3d Renderer::t_w_c(double t) const { return trajectory_.t_w_b(t) * scenario_.camera.mount; }

std::vector<Renderer::Instant> Renderer::instants(double t, bool led_on) const {
  const int samples = scenario_.motion_blur_samples;
  std::vector<Instant> result;
  for (int k = 0; k < samples; ++k) {
    const double when = exposure_sample_time(t, k);
    const Eigen::Isometry3d pose = t_w_c(when);
    Instant instant{pose, led_on, RingIllumination(scenario_.ring, pose), {}, {}};
    for (const Occluder& person : scenario_.people) instant.people.push_back(occluder_position(person, when));
    const double emitter_area = std::numbers::pi * std::pow(scenario_.landmark_emitters.radius, 2);
    for (const LedLandmark& landmark : scenario_.map.led_landmarks) {
      instant.landmark_radiance.push_back(
          landmark_intensity(landmark, scenario_.landmark_emitters.intensity, pose.translation()) / emitter_area);
    }
    result.push_back(std::move(instant));
  }
  return result;
}

double Renderer::exposure_sample_time(double t, int k) const {
  // Time samples spread evenly over the exposure, centred on t.
  const int samples = scenario_.motion_blur_samples;
  return t + scenario_.camera.exposure * ((k + 0.5) / samples - 0.5);
}

void Renderer::render(double t, bool led_on, std::span<float> radiance) const {
  const int samples = scenario_.motion_blur_samples;
  // A rolling shutter exposes row y line_time later than row y - 1: each row has its own
  // instants; under a global shutter every row shares row 0's.
  const double line_time = static_cast<double>(scenario_.camera.line_time_ns) * 1e-9;
  const bool rolling = line_time > 0;
  std::vector<std::vector<Instant>> row_instants(rolling ? static_cast<std::size_t>(height_) : 1);
  for_each_row(static_cast<int>(row_instants.size()), [&](int y) {
    row_instants[static_cast<std::size_t>(y)] = instants(t + y * line_time, led_on);
  });
  for_each_row(height_, [&](int y) {
    const std::vector<Instant>& at_row = row_instants[rolling ? static_cast<std::size_t>(y) : 0];
    for (int x = 0; x < width_; ++x) {
      float sum = 0;
      for (const Instant& instant : at_row) sum += pixel_radiance(instant, x, y);
      radiance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] =
          sum / static_cast<float>(samples);
    }
  });
  if (scenario_.landmark_emitters.psf_sigma > 0) {
    for (int k = 0; k < samples; ++k) {
      add_landmark_spots(scenario_, camera_, [&](double row) { return t_w_c(exposure_sample_time(t + row * line_time, k)); },
                         1.0 / samples, radiance);
    }
  }
}

float Renderer::pixel_radiance(const Instant& instant, int x, int y) const {
  const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  const Eigen::Matrix3d rotation = instant.t_w_c.linear();
  PixelCache cache;
  const double spread = spreads_[pixel];
  if (spread >= 0) {
    const Eigen::Vector3d centre = rotation * centres_[pixel].cast<double>();
    if (uniform_ceiling(instant, centre, spread)) return static_cast<float>(ray_radiance(instant, centre, cache));
  }
  const Eigen::Vector3f* bearing = &bearings_[pixel * static_cast<std::size_t>(samples_per_pixel_)];
  double sum = 0;
  for (int s = 0; s < samples_per_pixel_; ++s) {
    if (std::isnan(bearing[s].x())) continue;  // outside the lens: no light
    sum += ray_radiance(instant, rotation * bearing[s].cast<double>(), cache);
  }
  return static_cast<float>(sum / samples_per_pixel_);
}

bool Renderer::uniform_ceiling(const Instant& instant, const Eigen::Vector3d& d, double spread) const {
  const Room& room = scenario_.room;
  const Eigen::Vector3d& c = instant.t_w_c.translation();
  if (d.z() <= 1e-3) return false;
  const double t = (room.ceiling_height - c.z()) / d.z();
  // How far the pixel's rays land from the centre ray's hit, with a safety factor of 2: on the
  // ceiling the footprint stretches by 1 / cos(incidence) = 1 / d.z.
  const double reach = 2 * t * spread / d.z();
  if (reach >= ceiling_.cell_size()) return false;
  const Eigen::Vector3d p = c + t * d;
  if (!ceiling_.empty_near(p.x(), p.y())) return false;
  if (room.bounds) {
    const Eigen::Vector4d& b = *room.bounds;
    if (p.x() - reach < b[0] || p.x() + reach > b[2] || p.y() - reach < b[1] || p.y() + reach > b[3]) return false;
  }
  for (std::size_t i = 0; i < instant.people.size(); ++i) {
    const Occluder& person = scenario_.people[i];
    // A cylinder grown by the pixel's reach at the person's distance must miss the centre ray.
    const double grown = person.radius + 2 * spread * (c.head<2>() - instant.people[i]).norm() + 0.01;
    if ((c.head<2>() - instant.people[i]).norm() <= grown) return false;
    if (hit_cylinder(c, d, instant.people[i], grown, person.height + grown) < kInfinity) return false;
  }
  const double emitter = scenario_.landmark_emitters.radius;
  for (const LedLandmark& landmark : scenario_.map.led_landmarks) {
    const Eigen::Vector3d w = landmark.position - c;
    const double along = w.dot(d);
    if (along <= 0) continue;
    const double off_ray = std::sqrt(std::max(0.0, w.squaredNorm() - along * along));
    if (off_ray <= emitter + 2 * spread * along + 0.001) return false;
  }
  return true;
}

namespace {

// `radiance` at a point on a wall, with what the room's windows there add (they lie in the walls).
double with_windows(const Room& room, const Eigen::Vector3d& p, double radiance) {
  for (const Window& window : room.windows) {
    const Eigen::Vector3d low = window.corner_a.cwiseMin(window.corner_b).array() - 1e-3;
    const Eigen::Vector3d high = window.corner_a.cwiseMax(window.corner_b).array() + 1e-3;
    if ((p.array() >= low.array()).all() && (p.array() <= high.array()).all()) radiance += window.radiance;
  }
  return radiance;
}

}  // namespace

// Nearest of ceiling, walls (or floor) and people along the ray from the camera.
Renderer::RayHit Renderer::nearest_surface(const Instant& instant, const Eigen::Vector3d& d) const {
  const Room& room = scenario_.room;
  const Eigen::Vector3d& c = instant.t_w_c.translation();
  RayHit hit;
  if (d.z() > 1e-12) {
    hit.t = (room.ceiling_height - c.z()) / d.z();
    hit.surface = Surface::ceiling;
  }
  if (room.bounds) {
    const Eigen::Vector4d& b = *room.bounds;
    const auto exit = [&](double origin, double direction, double low, double high, Eigen::Vector3d normal) {
      if (std::abs(direction) < 1e-12) return;
      const double t = ((direction > 0 ? high : low) - origin) / direction;
      if (t > 0 && t < hit.t) {
        hit.t = t;
        hit.surface = Surface::wall;
        hit.wall_normal = direction > 0 ? Eigen::Vector3d(-normal) : normal;
      }
    };
    exit(c.x(), d.x(), b[0], b[2], Eigen::Vector3d::UnitX());
    exit(c.y(), d.y(), b[1], b[3], Eigen::Vector3d::UnitY());
    if (d.z() < -1e-12 && -c.z() / d.z() < hit.t) {
      hit.t = -c.z() / d.z();
      hit.surface = Surface::wall;
      hit.wall_normal = Eigen::Vector3d::UnitZ();
    }
  }
  for (std::size_t i = 0; i < instant.people.size(); ++i) {
    const Occluder& person = scenario_.people[i];
    const double t = hit_cylinder(c, d, instant.people[i], person.radius, person.height);
    if (t < hit.t) {
      hit.t = t;
      hit.surface = Surface::person;
      hit.person = i;
    }
  }
  return hit;
}

double Renderer::ray_radiance(const Instant& instant, const Eigen::Vector3d& d, PixelCache& cache) const {
  const Room& room = scenario_.room;
  const Eigen::Vector3d& c = instant.t_w_c.translation();
  const RayHit hit = nearest_surface(instant, d);
  const double t_hit = hit.t;
  // Active landmarks in front of the surface: small glowing spheres.
  const auto& landmarks = scenario_.map.led_landmarks;
  const double r2 = scenario_.landmark_emitters.radius * scenario_.landmark_emitters.radius;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const Eigen::Vector3d w = landmarks[i].position - c;
    const double along = w.dot(d);
    if (along <= 0 || along > t_hit || scenario_.landmark_emitters.psf_sigma > 0) continue;
    if (w.squaredNorm() - along * along <= r2) return instant.landmark_radiance[i];
  }

  if (hit.surface == Surface::none) return 0;
  const Eigen::Vector3d p = c + t_hit * d;
  const auto diffuse = [&](double reflectance, const Eigen::Vector3d& normal) {
    const double lit = room.ambient + (instant.led_on ? instant.ring.irradiance(p, normal) : 0);
    return reflectance * kInvPi * lit;
  };
  switch (hit.surface) {
    case Surface::ceiling: {
      const Eigen::Vector3d down(0, 0, -1);
      if (!cache.ceiling_seen) {
        cache.ceiling_seen = true;
        cache.ceiling = diffuse(room.ceiling_reflectance, down);
        cache.anchor = {p.x(), p.y()};
        cache.ceiling_empty = ceiling_.empty_near(p.x(), p.y());
      }
      const double step = std::max(std::abs(p.x() - cache.anchor.x()), std::abs(p.y() - cache.anchor.y()));
      if (cache.ceiling_empty && step < ceiling_.cell_size()) return cache.ceiling;
      const CeilingSample sample = ceiling_.at(p.x(), p.y());
      double radiance = cache.ceiling + sample.emitted;
      if (sample.retro && instant.led_on) {
        // Smooth across a pixel: evaluated once per pixel.
        if (cache.retro < 0) cache.retro = instant.ring.retro_radiance(p, down, scenario_.retro);
        radiance += cache.retro;
      }
      return radiance;
    }
    case Surface::wall: {
      if (cache.wall < 0) cache.wall = diffuse(room.wall_reflectance, hit.wall_normal);
      return with_windows(room, p, cache.wall);
    }
    case Surface::person: {
      if (cache.person < 0) {
        const Eigen::Vector2d radial = (Eigen::Vector2d(p.x(), p.y()) - instant.people[hit.person]).normalized();
        cache.person = diffuse(scenario_.people[hit.person].reflectance, Eigen::Vector3d(radial.x(), radial.y(), 0));
      }
      return cache.person;
    }
    case Surface::none: break;
  }
  return 0;
}

}  // namespace irloc::sim
