#pragma once
// What lies on the ceiling plane: retro-reflective dots, tape and clutter (strips, crescents), and
// lamps, indexed by a uniform grid so a ray's hit point finds the few shapes near it in constant time.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Material under a point of the ceiling.
struct CeilingSample {
  bool retro = false;   // dot, tape or clutter: lit by the robot's LEDs
  double emitted = 0;   // lamp radiance, W sr^-1 m^-2
};

class CeilingLayout {
 public:
  // The map's markers, and the room's lamps and clutter.
  CeilingLayout(const MarkerMap& map, const Room& room);

  // What is at ceiling point (x, y).
  CeilingSample at(double x, double y) const;

  // true when nothing lies within `cell_size()` of (x, y): the renderer then skips at() for
  // the other rays of the same pixel that land that close.
  bool empty_near(double x, double y) const;
  double cell_size() const { return cell_; }

  // Centres of every dot of every dot marker, in W (the renderer's ground truth of dots).
  static std::vector<Eigen::Vector3d> dot_centres(const DotMarker& marker);

 private:
  enum class Kind : std::uint8_t { dot, tape_side, tape_corner, half_disc, lamp_disc, lamp_rect };
  // A shape in the ceiling plane. Sides: origin = start corner, u along the side, v across it (a
  // strip of clutter is a solid side). Half discs: origin = centre, u toward the round half.
  struct Shape {
    Kind kind = Kind::dot;
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    Eigen::Vector2d u = Eigen::Vector2d::Zero(), v = Eigen::Vector2d::Zero();
    double length = 0, half_width = 0, half_length = 0;  // sides / corners / rectangles
    double radius = 0;                                   // discs
    double dash = 0, period = 0;                         // dashed sides; period 0 = solid
    double radiance = 0;                                 // lamps
  };
  bool contains(const Shape& shape, const Eigen::Vector2d& p) const;
  void add(const Shape& shape, Eigen::Vector2d low, Eigen::Vector2d high);
  void add_markers(const MarkerMap& map);
  void add_square_side(const SquareMarker& marker, int side);
  void add_clutter(const Room& room);
  void add_lamps(const Room& room);
  void build_grid();

  std::vector<Shape> shapes_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> bounds_;  // per shape
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 0.1;
  int columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> cell_start_;   // CSR: shapes of cell c are cell_shapes_[start[c]..start[c+1])
  std::vector<std::uint32_t> cell_shapes_;
  std::vector<std::uint8_t> occupied_near_;  // per cell: it or one of its 8 neighbours has shapes
};

}  // namespace irloc::sim
