// A mortar pass (contact/mortar_pass.hpp) on flat faces that do not match, pressed
// together by a uniform penetration: the static contact patch test. Every slave node
// gets kappa d integral N_I dA and every master node -kappa d integral N_J dA (the
// consistent forces of the uniform pressure kappa d), for 4- and 8-node faces, with any
// local search method; the slave-node points of the same faces do not.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "contact/contact_pass.hpp"
#include "contact/local_search.hpp"

namespace exdyn::contact {
namespace {

// A face of n x n segments over [0, 1]^2 at height z, its outward normal +z (up) or -z.
// Adds its nodes to x (ids from x.size()); returns its segments and, per node, the
// consistent area integral N_I dA.
struct Face {
  std::vector<SegmentNodes> segments;
  std::vector<std::uint32_t> nodes;
  std::vector<double> area;  // indexed by node id - nodes.front()
};

Face make_face(NodalVectors& x, int n, SegmentType type, double z, bool up) {
  Face face;
  const int per_side = type == SegmentType::quad4 ? n + 1 : 2 * n + 1;  // lattice points a side
  const auto first = std::uint32_t(x.size());
  const double h = 1.0 / (per_side - 1);
  std::vector<std::int64_t> id(std::size_t(per_side * per_side), -1);
  auto node = [&](int i, int j) {
    std::int64_t& k = id[std::size_t(j * per_side + i)];
    if (k < 0) {
      k = std::int64_t(x.size());
      x.x.push_back(i * h), x.y.push_back(j * h), x.z.push_back(z);  // (resize would zero them all)
      face.nodes.push_back(std::uint32_t(k));
    }
    return std::uint32_t(k);
  };
  const int step = type == SegmentType::quad4 ? 1 : 2;
  const double a = 1.0 / (n * n);  // a segment's area
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Lattice offsets of the nodes in Segment order (corners, then mid-sides), seen from
      // above; facing down, mirrored in xi2.
      const int I = step * i, J = step * j;
      std::array<std::array<int, 2>, 8> at{
          {{0, 0}, {step, 0}, {step, step}, {0, step}, {1, 0}, {2, 1}, {1, 2}, {0, 1}}};
      SegmentNodes s;
      s.type = type;
      for (int k = 0; k < node_count(type); ++k) {
        const int dj = up ? at[std::size_t(k)][1] : step - at[std::size_t(k)][1];
        s.nodes[std::size_t(k)] = node(I + at[std::size_t(k)][0], J + dj);
      }
      face.segments.push_back(s);
    }
  face.area.assign(face.nodes.size(), 0.0);
  for (const SegmentNodes& s : face.segments)
    for (int k = 0; k < node_count(type); ++k)
      face.area[s.nodes[std::size_t(k)] - first] +=
          type == SegmentType::quad4 ? a / 4 : (k < 4 ? -a / 12 : a / 3);
  return face;
}

void check_static_patch(SegmentType slave_type, int slave_n, SegmentType master_type, int master_n,
                        SearchMethod method) {
  const double kappa = 2.0e12, depth = 1.0e-6;  // Pa/m, m
  NodalVectors x;
  const Face master = make_face(x, master_n, master_type, 0.0, true);   // the lower body's top face
  const Face slave = make_face(x, slave_n, slave_type, -depth, false);  // the upper's bottom, pressed in
  ContactSurfaces surfaces;
  surfaces.mortar = true;
  surfaces.slave_segments = slave.segments;
  surfaces.slave_nodes = slave.nodes;
  surfaces.segments = master.segments;
  surfaces.segment_kappa.assign(slave.segments.size(), kappa);
  surfaces.segment_length.assign(slave.segments.size(), 0.1);
  surfaces.slave_area_per_mass.assign(slave.segments.size(), 1.0);
  surfaces.master_area_per_mass.assign(master.segments.size(), 1.0);
  surfaces.triangle_points = slave_type == SegmentType::quad8 || master_type == SegmentType::quad8 ? 6 : 3;
  surfaces.moving_nodes = master.nodes;
  surfaces.moving_nodes.insert(surfaces.moving_nodes.end(), slave.nodes.begin(), slave.nodes.end());
  ContactPassSettings settings;
  settings.project = select_method(method);
  settings.projection.method = method;
  settings.automatic_stiffness = false;
  settings.dt = 1.0;
  settings.search_distance = settings.margin = 0.05;
  ContactPassState state;
  NodalVectors u(x.size()), v(x.size()), force(x.size());
  std::vector<double> mass(x.size(), 1.0), gap(x.size(), 1.0);
  ContactStatistics statistics;
  ContactPhaseSeconds seconds;
  run_contact_pass(surfaces, settings, state, x, u, v, mass, force, gap, statistics, seconds);
  EXPECT_EQ(statistics.not_converged, 0);
  EXPECT_EQ(statistics.saddle_points, 0);
  EXPECT_GT(statistics.projections, 0);
  const double p = kappa * depth;  // Pa
  double worst = 0.0;
  for (std::size_t i = 0; i < slave.nodes.size(); ++i) {
    const std::uint32_t n = slave.nodes[i];
    worst = std::max(
        {worst, std::abs(force.z[n] - p * slave.area[i]), std::abs(force.x[n]), std::abs(force.y[n])});
  }
  for (std::size_t i = 0; i < master.nodes.size(); ++i) {
    const std::uint32_t n = master.nodes[i];
    worst = std::max(
        {worst, std::abs(force.z[n] + p * master.area[i]), std::abs(force.x[n]), std::abs(force.y[n])});
  }
  // Nelder-Mead stops when its simplex is tolerance (1e-10) small: xi to that, not to round-off.
  EXPECT_LE(worst / p, method == SearchMethod::simplex ? 1e-9 : 1e-13)
      << name(slave_type) << " " << slave_n << " on " << name(master_type) << " " << master_n << ", "
      << name(method);
  for (std::uint32_t n : slave.nodes) EXPECT_NEAR(gap[n], -depth, 1e-15);
}

TEST(MortarPass, FlatNonMatchingFacesCarryAUniformPressureExactly) {
  for (SearchMethod method :
       {SearchMethod::newton, SearchMethod::bfgs, SearchMethod::simplex, SearchMethod::robust}) {
    check_static_patch(SegmentType::quad4, 3, SegmentType::quad4, 4, method);
    check_static_patch(SegmentType::quad4, 2, SegmentType::quad4, 5, method);
    check_static_patch(SegmentType::quad8, 3, SegmentType::quad8, 4, method);
    check_static_patch(SegmentType::quad4, 3, SegmentType::quad8, 2, method);
    check_static_patch(SegmentType::quad8, 2, SegmentType::quad4, 5, method);
  }
}

}  // namespace
}  // namespace exdyn::contact
