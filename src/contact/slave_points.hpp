// The slave points of a contact surface (ContactSurfaces: slave nodes, or the Gauss
// points of the slave segments): where they are, and the nodes their forces go to.
// Shared by the contact pass and the rigid wall pass.
#pragma once

#include <array>
#include <cstdint>

#include "common/nodal_vectors.hpp"
#include "common/parallel.hpp"
#include "contact/contact_pass.hpp"

namespace exdyn::contact {

inline Vec3 current_position(const NodalVectors& x_ref, const NodalVectors& u, std::uint32_t node) {
  return {x_ref.x[node] + u.x[node], x_ref.y[node] + u.y[node], x_ref.z[node] + u.z[node]};
}

// A segment at the current configuration x = x_ref + u (m).
inline Segment current_segment(const SegmentNodes& ids, const NodalVectors& x_ref, const NodalVectors& u) {
  Segment segment;
  segment.type = ids.type;
  for (int i = 0; i < node_count(ids.type); ++i)
    segment.nodes[std::size_t(i)] = current_position(x_ref, u, ids.nodes[std::size_t(i)]);
  return segment;
}

// The current position of every slave point into `points` (m): a slave node's, or a
// Gauss point's y(xi) = sum N_I(xi) y_I on its slave segment. On the threads in chunks
// of 256 points, each point its own: the gathers from the nodal arrays miss the caches
// on a large model (alone, 0.8 % of the step of the plate impact at 320,000 bricks).
inline void update_slave_points(const ContactSurfaces& surfaces, const NodalVectors& x_ref,
                                const NodalVectors& u, NodalVectors& points) {
  const std::size_t n_points = surfaces.point_count();
  points.resize(n_points);
  for_each_chunk(
      n_points,
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t p = begin; p < end; ++p) {
          Vec3 x{};
          if (!surfaces.quadrature) {
            x = current_position(x_ref, u, surfaces.slave_nodes[p]);
          } else {
            const QuadraturePoint& q = surfaces.quadrature_points[p];
            const SegmentNodes& ids = surfaces.slave_segments[q.segment];
            const std::array<double, 8> N = shape_functions(ids.type, q.xi);
            for (int i = 0; i < node_count(ids.type); ++i)
              x = x + N[std::size_t(i)] * current_position(x_ref, u, ids.nodes[std::size_t(i)]);
          }
          points.x[p] = x.x;
          points.y[p] = x.y;
          points.z[p] = x.z;
        }
      },
      256);
}

// The nodes a slave point's force goes to and their weights: the slave node with
// weight 1, or a Gauss point's segment nodes with N_I(xi).
struct SlaveSide {
  int count = 1;
  std::array<std::uint32_t, 8> nodes{};
  std::array<double, 8> weights{};
};

inline SlaveSide slave_side(const ContactSurfaces& surfaces, std::size_t p) {
  SlaveSide side;
  if (!surfaces.quadrature) {
    side.nodes[0] = surfaces.slave_nodes[p];
    side.weights[0] = 1.0;
    return side;
  }
  const QuadraturePoint& q = surfaces.quadrature_points[p];
  const SegmentNodes& ids = surfaces.slave_segments[q.segment];
  side.count = node_count(ids.type);
  side.nodes = ids.nodes;
  side.weights = shape_functions(ids.type, q.xi);
  return side;
}

// The slave point's velocity sum w_I v_I (m/s) and its inverse mass sum w_I^2 / m_I (1/kg).
struct SlaveMotion {
  Vec3 velocity{};
  double inverse_mass = 0.0;
};

inline SlaveMotion slave_motion(const SlaveSide& side, const NodalVectors& v,
                                const std::vector<double>& mass) {
  SlaveMotion motion;
  for (int i = 0; i < side.count; ++i) {
    const std::uint32_t node = side.nodes[std::size_t(i)];
    const double w = side.weights[std::size_t(i)];
    motion.velocity = motion.velocity + w * Vec3{v.x[node], v.y[node], v.z[node]};
    motion.inverse_mass += w * w / mass[node];
  }
  return motion;
}

// Adds F (N) to the slave point's nodes, w_I F each.
inline void add_to_slave(const SlaveSide& side, Vec3 F, NodalVectors& force) {
  for (int i = 0; i < side.count; ++i) {
    const std::uint32_t node = side.nodes[std::size_t(i)];
    const double w = side.weights[std::size_t(i)];
    force.x[node] += w * F.x;
    force.y[node] += w * F.y;
    force.z[node] += w * F.z;
  }
}

// The same as records of slave point p (slots 0 .. count - 1).
inline void add_to_slave(const SlaveSide& side, Vec3 F, std::size_t p, RecordSink& records) {
  for (int i = 0; i < side.count; ++i) {
    const double w = side.weights[std::size_t(i)];
    records.add(p, i, side.nodes[std::size_t(i)], w * F.x, w * F.y, w * F.z);
  }
}

}  // namespace exdyn::contact
