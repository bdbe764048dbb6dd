// The contact figures of a step on many ranks: each rank's statistics, pass forces and
// contact power gathered and added rank after rank, so every rank reports the same
// figures as one process would (distributed_contact.hpp, docs/parallel.md).
#include <algorithm>
#include <array>
#include <vector>

#include "common/timer.hpp"
#include "ranks/distributed_contact.hpp"

namespace exdyn::solver {

namespace {

// The figures of a step, packed per rank: per pair and wall its statistics, per pass
// its state's, per wall its state's; then the contact power.
constexpr std::size_t statistics_size = 9, pass_size = 16;

void pack(const contact::ContactStatistics& s, std::vector<double>& out) {
  out.insert(out.end(), {double(s.projections), double(s.iterations), double(s.not_converged),
                         double(s.saddle_points), double(s.max_iterations), s.max_penetration_over_h,
                         double(s.deepest_node), s.max_pair_stiffness, double(s.fallbacks)});
}
// (sums: |F_n| and |F_t| summed over the points, the points pressed; zero for a wall.)
void pack(contact::Vec3 a, contact::Vec3 b, contact::Vec3 c, double penetration, long slipping, long sticking,
          double friction_work, std::array<double, 3> sums, std::vector<double>& out) {
  out.insert(out.end(), {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, penetration, double(slipping),
                         double(sticking), friction_work, sums[0], sums[1], sums[2]});
}

// Rank r's figures added to `total` (r = 0: `total` is rank 0's).
void add_statistics(const double* f, contact::ContactStatistics& s) {
  s.projections += long(f[0]);
  s.iterations += long(f[1]);
  s.not_converged += long(f[2]);
  s.saddle_points += long(f[3]);
  s.max_iterations = std::max(s.max_iterations, long(f[4]));
  if (f[5] > s.max_penetration_over_h) s.max_penetration_over_h = f[5], s.deepest_node = std::uint32_t(f[6]);
  s.max_pair_stiffness = std::max(s.max_pair_stiffness, f[7]);
  s.fallbacks += long(f[8]);
}
struct PassFigures {
  contact::Vec3 a{}, b{}, c{};
  double penetration = 0.0, slipping = 0.0, sticking = 0.0, friction_work = 0.0;
  double normal_sum = 0.0, tangential_sum = 0.0, points = 0.0;
};
void add_pass(const double* f, PassFigures& t) {
  t.a = t.a + contact::Vec3{f[0], f[1], f[2]};
  t.b = t.b + contact::Vec3{f[3], f[4], f[5]};
  t.c = t.c + contact::Vec3{f[6], f[7], f[8]};
  t.penetration = std::max(t.penetration, f[9]);
  t.slipping += f[10];
  t.sticking += f[11];
  t.friction_work += f[12];
  t.normal_sum += f[13];
  t.tangential_sum += f[14];
  t.points += f[15];
}

}  // namespace

double reduce_contact_figures(ContactModel& contact, DistributedContact& dc, double power) {
  std::vector<double> mine;
  for (const contact::ContactStatistics& s : dc.local_statistics) pack(s, mine);
  std::size_t k = 0;
  for (const ContactPair& pair : contact.pairs)
    for (const contact::ContactPassState& s : pair.states)
      pack(s.slave_force, s.slave_normal_force, s.slave_tangential_force, s.max_penetration, s.slipping,
           s.sticking, dc.passes[k++].local_friction_work,
           {s.normal_force_sum, s.tangential_force_sum, double(s.points_in_contact)}, mine);
  for (const RigidWall& wall : contact.walls) {
    const contact::WallState& s = wall.state;
    pack(s.force, s.normal_force, s.tangential_force, s.max_penetration, s.slipping, s.sticking,
         dc.passes[k++].local_friction_work, {0.0, 0.0, 0.0}, mine);
  }
  mine.push_back(power);
  const std::size_t n = mine.size();
  std::vector<double> all;
  {
    const ScopedTimer timer(dc.wait_seconds);
    all = mpi::all_gather(dc.comm, mine.data(), int(n));
  }
  dc.bytes_sent += double(sizeof(double) * n) * double(dc.comm.size - 1);
  dc.messages_sent += double(dc.comm.size - 1);

  // Rank after rank.
  const std::size_t contacts = dc.local_statistics.size();
  std::vector<contact::ContactStatistics> statistics(contacts);
  std::vector<PassFigures> passes(dc.passes.size());
  double total_power = 0.0;
  for (int r = 0; r < dc.comm.size; ++r) {
    const double* f = all.data() + n * std::size_t(r);
    for (std::size_t c = 0; c < contacts; ++c) add_statistics(f + statistics_size * c, statistics[c]);
    const double* g = f + statistics_size * contacts;
    for (std::size_t p = 0; p < passes.size(); ++p) add_pass(g + pass_size * p, passes[p]);
    total_power = r == 0 ? f[n - 1] : total_power + f[n - 1];
  }
  k = 0;
  std::size_t c = 0;
  for (ContactPair& pair : contact.pairs) {
    pair.statistics = statistics[c++];
    for (contact::ContactPassState& s : pair.states) {
      const PassFigures& t = passes[k++];
      s.slave_force = t.a, s.slave_normal_force = t.b, s.slave_tangential_force = t.c;
      s.max_penetration = t.penetration;
      s.slipping = long(t.slipping), s.sticking = long(t.sticking);
      s.friction_work = t.friction_work;
      s.normal_force_sum = t.normal_sum, s.tangential_force_sum = t.tangential_sum;
      s.points_in_contact = long(t.points);
    }
    pair.follow_peaks();
  }
  for (RigidWall& wall : contact.walls) {
    wall.statistics = statistics[c++];
    contact::WallState& s = wall.state;
    const PassFigures& t = passes[k++];
    s.force = t.a, s.normal_force = t.b, s.tangential_force = t.c;
    s.max_penetration = t.penetration;
    s.slipping = long(t.slipping), s.sticking = long(t.sticking);
    s.friction_work = t.friction_work;
    wall.max_force = std::max(wall.max_force, contact::norm(s.force));
  }
  return total_power;
}

ContactShareFigures contact_share_figures(const DistributedContact& dc) {
  ContactShareFigures f = dc.largest;
  const double steps = double(std::max(dc.steps, 1L));
  f.messages_per_step = dc.messages_sent / steps;
  f.bytes_per_step = dc.bytes_sent / steps;
  f.wait_seconds = dc.wait_seconds;
  return f;
}
}  // namespace exdyn::solver
