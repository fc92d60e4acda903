#pragma once

#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"
#include "engine/region.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace mpile {

/// The known shape of a structure in the r-y plane: a closed polygon, counter-clockwise, whose
/// edge k (vertex k to vertex k + 1) belongs to surface edge_surface[k], or to none (-1: an edge
/// the soil never touches, such as a pile head above the ground, which then gives no area). The
/// outward normal of an edge with direction (dr, dy) is (dy, -dr) / length. A rigid body's outline
/// moves with it.
struct StructureOutline {
  std::vector<std::array<double, 2>> vertices;
  std::vector<int> edge_surface;

  /// The axis-aligned rectangle [r0, r1] x [y0, y1] with surfaces for its bottom, right, top and
  /// left edges (for an open-ended pile: tip, outer shaft, head, inner shaft).
  static StructureOutline rectangle(double r0, double r1, double y0, double y1, int bottom,
                                    int right, int top, int left);
  void translate(double dr, double dy);
  /// Rotates about (r, y) by angle (rad, counter-clockwise).
  void rotate(double angle, double r, double y);

  /// Whether (r, y) lies strictly inside (crossing number: any simple polygon, convex or not).
  bool contains(double r, double y) const;
  /// The smallest axis-aligned box holding the outline: {r_min, r_max, y_min, y_max}.
  std::array<double, 4> bounds() const;
};

/// Edges of the regular polygon that stands for a circle's outline: convex, as OutlineDistance
/// needs, and short of the circle's length by 4e-4 (1 - sin(x) / x, x = pi / 64) and of a sphere's
/// area by 1.2e-3, so that contact areas and an adhesion's resultant are that close.
constexpr int circle_outline_edges = 64;

/// The outline of a structure's region: a rectangle's or polygon's vertices (counter-clockwise,
/// edge k from vertex k to the next) with surface[k] for edge k; for a circle, the regular polygon
/// of circle_outline_edges inscribed in it, every edge on surface[0], with a vertex at the bottom.
/// In axisymmetric mode a circle centred on the axis (a sphere) is outlined by the half at r >= 0,
/// closed along the axis by an edge that is no contact surface.
StructureOutline region_outline(const Region& region, GeometryMode mode,
                                const std::vector<int>& surface);

/// The most surfaces one contact structure may have (the per-step sums are fixed-size).
constexpr std::size_t max_contact_surfaces = 8;

/// Signed distance from an outline, positive outside: the largest distance from an edge's line
/// (exact along the edges of a convex outline, an underestimate beyond its corners). The edge lines
/// are formed once, so that the per-particle evaluation is a few multiply-adds.
class OutlineDistance {
public:
  explicit OutlineDistance(const StructureOutline& outline);
  double operator()(double r, double y) const {
    double distance = -std::numeric_limits<double>::infinity();
    for (const auto& [n_r, n_y, offset] : lines_) {
      distance = std::max(distance, n_r * r + n_y * y - offset);
    }
    return distance;
  }
  /// The signed distance and the outward normal of the edge that gives it.
  struct Nearest {
    double distance;
    double n_r;
    double n_y;
  };
  Nearest nearest(double r, double y) const {
    Nearest best{-std::numeric_limits<double>::infinity(), 0.0, 0.0};
    for (const auto& [n_r, n_y, offset] : lines_) {
      const double d = n_r * r + n_y * y - offset;
      if (d > best.distance) {
        best = {d, n_r, n_y};
      }
    }
    return best;
  }

private:
  std::vector<std::array<double, 3>> lines_; // outward unit normal and offset of each edge
};

/// The soil's gap from an outline on either side of a node along the outline (below and above it
/// in r, or in y for an outline nearer vertical): the smallest gap of a soil particle within a cell
/// of the node on that side, and that particle's distance from the node along the tangent.
struct SurfaceGap {
  double below = std::numeric_limits<double>::infinity();
  double below_distance = 0.0;
  double above = std::numeric_limits<double>::infinity();
  double above_distance = 0.0;

  /// Takes a particle's gap at signed distance `offset` from the node along the tangent.
  void add(double gap, double offset) {
    if (offset <= 0.0) {
      if (gap < below) {
        below = gap;
        below_distance = -offset;
      }
    } else if (gap < above) {
      above = gap;
      above_distance = offset;
    }
  }
  /// The gap linearly interpolated to the node between its two sides; where the soil lies on one
  /// side only, that side's; +inf where it lies on neither.
  double at_node() const {
    if (below == std::numeric_limits<double>::infinity() ||
        above == std::numeric_limits<double>::infinity()) {
      return std::min(below, above);
    }
    const double span = below_distance + above_distance;
    return span > 0.0 ? (below * above_distance + above * below_distance) / span
                      : std::min(below, above);
  }
};

/// Contact between the soil (field 0) and one structure with a field of its own (physics.md
/// section 5): Coulomb friction mu and adhesion c_a, normals from the outline when the structure
/// has one, from the structure's mass gradient otherwise. The per-node arrays are sized to the grid
/// and refreshed every step; forces are those of the soil on the structure.
struct ContactPair {
  std::string name; // the structure's body name
  std::uint16_t structure_body = 0;
  int field = 1;
  int rigid_body = -1; // index into the scene's rigid bodies, -1 for a deformable structure
  double friction = 0.0;
  double adhesion = 0.0; // Pa
  std::vector<std::string> surfaces;
  std::optional<StructureOutline> outline;

  // Per node, from the outline: contact area (m^2, per radian in axisymmetric mode), its share on
  // each surface (node * surfaces + surface) and the structure's outward unit normal; and for every
  // pair, the force of the last step (N [/rad]).
  std::vector<double> area;
  std::vector<double> surface_area;
  std::vector<std::array<double, 2>> normal;
  std::vector<std::array<double, 3>> node_force;
  /// Per node, the kinetic energy the last step's correction took (J [/rad], >= 0): the relative
  /// motion it removed, normal and tangential.
  std::vector<double> node_dissipation;
  // Per node, from the contact pass after the momentum balance: 0 not in contact, 1 sliding, 2
  // sticking, and the normal used. After the MUSL remap the same nodes get the same kind of
  // correction again, without a new approach test, so that the strain increment sees the motion the
  // particles made (as at a support); deciding contact anew there would let the strain see an
  // opening or a slip the positions never made, and feed energy into the soil.
  std::vector<std::uint8_t> state;
  std::vector<std::array<double, 2>> contact_normal;
  /// The nodes where node_force, node_dissipation, state and contact_normal were last written;
  /// outside it they are zero (free), as allocate leaves them.
  NodeBox written;
  std::vector<int> outlined_nodes; // nodes the outline gave an area, cleared before the next step
  /// Per node, with an outline: the smallest gap between the outline and the domain of a soil
  /// particle in the node's cells (distance minus half the particle's size; <= 0: touching).
  /// Formed at the nodes of the structure field's reach only, the only nodes it is read at.
  /// Contact needs it: a node both bodies occupy may still have a gap smaller than a cell between
  /// them, which the nodal test alone would never let close.
  std::vector<double> gap;
  /// With an outline, whether contact at a node on a straight run of one surface along r or y needs
  /// the soil's surface at the node to reach the outline (`gap = "surface"`), rather than any
  /// particle of its cells.
  bool surface_gap_at_node = false;
  /// Per node, with surface_gap_at_node: the soil's gap on either side of the node along the
  /// outline's tangent (SurfaceGap), which interpolated to the node gives the gap of the soil's
  /// surface at the node itself.
  std::vector<SurfaceGap> surface_gap;

  /// Per node, with pore water in the soil: the pore pressure's part of node_force, the pore
  /// water's force along the contact normal (its pressure on the wall; empty without water).
  std::vector<std::array<double, 2>> node_pore_force;

  // Sums of the last step per surface: (F_r, F_y, F_theta) and the torque about the axis; with
  // pore water, the pore pressure's part of (F_r, F_y) (the rest is the effective stress's).
  std::vector<std::array<double, 3>> surface_force;
  std::vector<double> surface_torque;
  std::vector<std::array<double, 2>> surface_pore_force;

  std::size_t surface_count() const { return surfaces.size(); }
  /// Sizes the per-node arrays to the grid (once, before the first step).
  void allocate(std::size_t node_count);
};

/// Fills area, surface_area and normal of the nodes the outline touches: for each edge, the
/// integral of N_i (times r in axisymmetric mode) along the edge, by two-point Gauss on each piece
/// of the edge within one cell (exact: the integrand is at most cubic along a piece). The areas of
/// an edge sum to its length (times its mean radius), so a uniform traction gets its exact
/// resultant; a node at a corner gets the area-weighted mean normal of its edges.
void integrate_outline(const Grid& grid, GeometryMode mode, ContactPair& pair);

/// The areas of one contact surface that unit resistances are taken over (m^2, per radian in
/// axisymmetric mode, per metre in plane strain): its plan area, the projection on a horizontal
/// plane (integral of r |dr| along its edges), over which an end bearing is quoted (a cone's q_c,
/// a pile tip's q_b); and its side area, the projection on a vertical cylinder (integral of r
/// |dy|), over which a shaft friction is quoted (a CPT sleeve's f_s).
struct SurfaceAreas {
  double plan = 0.0;
  double side = 0.0;
};

/// Those areas for each of `surfaces` surfaces of the outline, exact for its straight edges.
std::vector<SurfaceAreas> surface_areas(const StructureOutline& outline, std::size_t surfaces,
                                        GeometryMode mode);

/// The outward normal of the edge of surface `surface` nearest to (r, y): the normal a tip corner
/// node's traction acts along on that surface's share of its area.
std::array<double, 2> nearest_edge_normal(const StructureOutline& outline, double r, double y,
                                          int surface);

/// An edge's outward normal and the surface the edge belongs to.
struct EdgeNormal {
  std::array<double, 2> normal{0.0, 0.0};
  int surface = 0;
};

/// Normal and surface of a node inside the outline: those of the nearest edge, and where several
/// edges are as near to rounding, of the one whose normal points most along `direction`. Contact
/// passes the direction the soil moves into the structure (minus the relative velocity), so that
/// soil reaching the middle of a wall from either face meets that face.
EdgeNormal facing_edge_normal(const StructureOutline& outline, double r, double y,
                              const std::array<double, 2>& direction);

} // namespace mpile
