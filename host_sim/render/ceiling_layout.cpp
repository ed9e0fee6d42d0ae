#include "host_sim/render/ceiling_layout.hpp"

#include <algorithm>
#include <cmath>

namespace irloc::sim {
namespace {

// Weights of the code cells (docs/markers.md): kCodeWeight[i][j], 0 for O, X, Y and the corner.
// The renderer keeps its own copy of the table and of the marker axes, written from the spec, on
// purpose: ground truth drawn with the decoder's own table could not catch a wrong entry in it.
// tests/sim/render_test.cpp checks the two against each other for every ID.
constexpr int kCodeWeight[4][4] = {
    {0, 0x020, 0x200, 0},
    {0x002, 0x010, 0x100, 0x800},
    {0x001, 0x008, 0x080, 0x400},
    {0, 0x004, 0x040, 0},
};

Eigen::Vector2d xy(const Eigen::Vector3d& p) { return {p.x(), p.y()}; }

}  // namespace

std::vector<Eigen::Vector3d> CeilingLayout::dot_centres(const DotMarker& marker) {
  // M axes in W for a ceiling marker: x = (cos, sin, 0), y = (sin, -cos, 0).
  const Eigen::Vector3d x_axis(std::cos(marker.yaw), std::sin(marker.yaw), 0);
  const Eigen::Vector3d y_axis(std::sin(marker.yaw), -std::cos(marker.yaw), 0);
  std::vector<Eigen::Vector3d> centres;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const bool direction_dot = (i == 0 && j == 0) || (i == 0 && j == 3) || (i == 3 && j == 0);
      const bool code_dot = kCodeWeight[i][j] != 0 && (marker.id & kCodeWeight[i][j]) != 0;
      if (direction_dot || code_dot) {
        centres.push_back(marker.origin + marker.pitch * (j * x_axis + i * y_axis));
      }
    }
  }
  return centres;
}

CeilingLayout::CeilingLayout(const MarkerMap& map, const Room& room) {
  add_markers(map);
  add_clutter(room);
  add_lamps(room);
  build_grid();
}

void CeilingLayout::add_markers(const MarkerMap& map) {
  for (const DotMarker& marker : map.dot_markers) {
    for (const Eigen::Vector3d& centre : dot_centres(marker)) {
      Shape dot{};
      dot.kind = Kind::dot;
      dot.origin = xy(centre);
      dot.radius = marker.radius;
      const Eigen::Vector2d extent(marker.radius, marker.radius);
      add(dot, dot.origin - extent, dot.origin + extent);
    }
  }
  for (const SquareMarker& marker : map.square_markers) {
    for (int side = 0; side < 4; ++side) add_square_side(marker, side);
  }
}

// A side of a square's tape (c0 -> c1 solid, the others dashed) and the tape's corner at its start.
void CeilingLayout::add_square_side(const SquareMarker& marker, int side) {
  const Eigen::Vector2d start = xy(marker.corners[static_cast<std::size_t>(side)]);
  const Eigen::Vector2d end = xy(marker.corners[static_cast<std::size_t>((side + 1) % 4)]);
  Shape tape{};
  tape.kind = Kind::tape_side;
  tape.origin = start;
  tape.length = (end - start).norm();
  tape.u = (end - start) / tape.length;
  tape.v = {-tape.u.y(), tape.u.x()};
  tape.half_width = marker.tape_width / 2;
  if (side != 0) {  // c0 -> c1 is solid, the others dashed
    tape.dash = marker.dash;
    tape.period = marker.dash + marker.gap;
  }
  const Eigen::Vector2d pad(tape.half_width, tape.half_width);
  add(tape, start.cwiseMin(end) - pad, start.cwiseMax(end) + pad);

  Shape corner = tape;
  corner.kind = Kind::tape_corner;
  corner.half_length = tape.half_width;
  const Eigen::Vector2d reach = pad * std::sqrt(2.0);
  add(corner, start - reach, start + reach);
}

void CeilingLayout::add_clutter(const Room& room) {
  for (const CeilingClutter& clutter : room.clutter) {
    const Eigen::Vector2d axis(std::cos(clutter.yaw), std::sin(clutter.yaw));
    Shape shape{};
    shape.u = axis;
    if (clutter.kind == CeilingClutter::Kind::strip) {
      shape.kind = Kind::tape_side;
      shape.origin = clutter.centre - axis * clutter.length / 2;
      shape.length = clutter.length;
      shape.v = {-axis.y(), axis.x()};
      shape.half_width = clutter.width / 2;
      const Eigen::Vector2d end = clutter.centre + axis * clutter.length / 2;
      const Eigen::Vector2d pad(shape.half_width, shape.half_width);
      add(shape, shape.origin.cwiseMin(end) - pad, shape.origin.cwiseMax(end) + pad);
    } else {
      shape.kind = Kind::half_disc;
      shape.origin = clutter.centre;
      shape.radius = clutter.radius;
      const Eigen::Vector2d extent(clutter.radius, clutter.radius);
      add(shape, clutter.centre - extent, clutter.centre + extent);
    }
  }
}

void CeilingLayout::add_lamps(const Room& room) {
  for (const Lamp& lamp : room.lamps) {
    Shape shape{};
    shape.origin = lamp.centre;
    shape.radiance = lamp.radiance;
    if (lamp.radius > 0) {
      shape.kind = Kind::lamp_disc;
      shape.radius = lamp.radius;
      const Eigen::Vector2d extent(lamp.radius, lamp.radius);
      add(shape, lamp.centre - extent, lamp.centre + extent);
    } else {
      shape.kind = Kind::lamp_rect;
      shape.u = lamp.size / 2;  // half sizes along W x and y
      add(shape, lamp.centre - shape.u, lamp.centre + shape.u);
    }
  }
}

void CeilingLayout::add(const Shape& shape, Eigen::Vector2d low, Eigen::Vector2d high) {
  shapes_.push_back(shape);
  bounds_.emplace_back(low, high);
}

void CeilingLayout::build_grid() {
  if (shapes_.empty()) return;
  Eigen::Vector2d low = bounds_.front().first, high = bounds_.front().second;
  for (const auto& [a, b] : bounds_) {
    low = low.cwiseMin(a);
    high = high.cwiseMax(b);
  }
  origin_ = low;
  columns_ = static_cast<int>(std::ceil((high.x() - low.x()) / cell_)) + 1;
  rows_ = static_cast<int>(std::ceil((high.y() - low.y()) / cell_)) + 1;
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(columns_ * rows_));
  for (std::size_t s = 0; s < shapes_.size(); ++s) {
    const auto& [a, b] = bounds_[s];
    const int c0 = static_cast<int>((a.x() - origin_.x()) / cell_), c1 = static_cast<int>((b.x() - origin_.x()) / cell_);
    const int r0 = static_cast<int>((a.y() - origin_.y()) / cell_), r1 = static_cast<int>((b.y() - origin_.y()) / cell_);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) cells[static_cast<std::size_t>(r * columns_ + c)].push_back(static_cast<std::uint32_t>(s));
    }
  }
  cell_start_.push_back(0);
  for (const auto& cell : cells) {
    cell_shapes_.insert(cell_shapes_.end(), cell.begin(), cell.end());
    cell_start_.push_back(static_cast<std::uint32_t>(cell_shapes_.size()));
  }
  occupied_near_.assign(cells.size(), 0);
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < columns_; ++c) {
      if (cells[static_cast<std::size_t>(r * columns_ + c)].empty()) continue;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (r + dr >= 0 && r + dr < rows_ && c + dc >= 0 && c + dc < columns_) {
            occupied_near_[static_cast<std::size_t>((r + dr) * columns_ + c + dc)] = 1;
          }
        }
      }
    }
  }
}

bool CeilingLayout::empty_near(double x, double y) const {
  if (shapes_.empty()) return true;
  // One cell of margin around the grid: everything outside it is empty.
  const double fc = (x - origin_.x()) / cell_, fr = (y - origin_.y()) / cell_;
  if (fc < -1 || fr < -1 || fc >= columns_ + 1 || fr >= rows_ + 1) return true;
  const int c = std::clamp(static_cast<int>(std::floor(fc)), 0, columns_ - 1);
  const int r = std::clamp(static_cast<int>(std::floor(fr)), 0, rows_ - 1);
  return occupied_near_[static_cast<std::size_t>(r * columns_ + c)] == 0;
}

bool CeilingLayout::contains(const Shape& shape, const Eigen::Vector2d& p) const {
  const Eigen::Vector2d d = p - shape.origin;
  switch (shape.kind) {
    case Kind::dot:
    case Kind::lamp_disc:
      return d.squaredNorm() <= shape.radius * shape.radius;
    case Kind::half_disc:
      return d.squaredNorm() <= shape.radius * shape.radius && d.dot(shape.u) >= 0;
    case Kind::lamp_rect:
      return std::abs(d.x()) <= shape.u.x() && std::abs(d.y()) <= shape.u.y();
    case Kind::tape_corner:
      return std::abs(d.dot(shape.u)) <= shape.half_length && std::abs(d.dot(shape.v)) <= shape.half_length;
    case Kind::tape_side: {
      const double s = d.dot(shape.u);
      if (s < 0 || s > shape.length || std::abs(d.dot(shape.v)) > shape.half_width) return false;
      return shape.period == 0 || std::fmod(s, shape.period) < shape.dash;
    }
  }
  return false;
}

CeilingSample CeilingLayout::at(double x, double y) const {
  CeilingSample sample;
  if (shapes_.empty()) return sample;
  const double fc = (x - origin_.x()) / cell_, fr = (y - origin_.y()) / cell_;
  if (fc < 0 || fr < 0 || fc >= columns_ || fr >= rows_) return sample;
  const auto cell = static_cast<std::size_t>(static_cast<int>(fr) * columns_ + static_cast<int>(fc));
  const Eigen::Vector2d p(x, y);
  for (std::uint32_t i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i) {
    const Shape& shape = shapes_[cell_shapes_[i]];
    if (!contains(shape, p)) continue;
    if (shape.kind == Kind::lamp_disc || shape.kind == Kind::lamp_rect) {
      sample.emitted += shape.radiance;
    } else {
      sample.retro = true;
    }
  }
  return sample;
}

}  // namespace irloc::sim
