// What the time loop reports (step_report.hpp).
#include "solver/step_report.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "common/parallel.hpp"

namespace exdyn::solver {

// The node with the largest |v|_1 (m/s): where an instability grows fastest. On
// many ranks the fastest of every rank's owned nodes (ties: the lowest node).
std::string describe_fastest_node(const Decomposition& d, const NodalVectors& velocity) {
  std::size_t fastest = 0;
  double largest = -1.0;
  for (std::size_t i = 0; i < velocity.size(); ++i) {
    if (!d.owned.empty() && d.owned[i] == 0) continue;
    const double speed = std::abs(velocity.x[i]) + std::abs(velocity.y[i]) + std::abs(velocity.z[i]);
    if (speed > largest) largest = speed, fastest = i;
  }
  const double mine[2] = {largest, double(global_node_id(d, static_cast<std::uint32_t>(fastest)))};
  const std::vector<double> all = mpi::all_gather(d.comm, mine, 2);
  double node = all[1];
  largest = all[0];
  for (std::size_t r = 1; r < all.size() / 2; ++r)
    if (all[2 * r] > largest || (all[2 * r] == largest && all[2 * r + 1] < node))
      largest = all[2 * r], node = all[2 * r + 1];
  char text[96];
  std::snprintf(text, sizeof text, "the fastest node is %.0f, |v|_1 = %.3g m/s", node, largest);
  return text;
}

// Names the first node with a non-finite acceleration, velocity or displacement,
// else the first element with a non-finite stress, else the fastest node. Every
// rank calls it; the message is that of the lowest rank that found one.
std::string describe_non_finite(const Model& model, Decomposition& d, State& state) {
  forces_of_this_step(model, d, state);
  compute_accelerations(model, state);
  const std::pair<const char*, const NodalVectors*> fields[] = {{"acceleration", &state.acceleration},
                                                                {"velocity", &state.velocity},
                                                                {"displacement", &state.displacement}};
  std::string found;
  for (const auto& [label, field] : fields) {
    for (int c = 0; c < 3 && found.empty(); ++c) {
      const auto& values = field->component(c);
      for (std::size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i])) {
          found = std::string("non-finite ") + label + " at node " +
                  std::to_string(global_node_id(d, static_cast<std::uint32_t>(i))) + " (component " +
                  "xyz"[c] + ")";
          break;
        }
    }
    if (!found.empty()) break;
  }
  for (std::size_t k = 0; k < state.stress.size() && found.empty(); ++k)
    if (!std::isfinite(state.stress[k]))
      found = "non-finite stress in element " +
              std::to_string(global_element_id(d, static_cast<std::uint32_t>(k / 6))) + " (component " +
              std::to_string(k % 6) + " of xx yy zz xy yz xz)";
  found = mpi::first_message(d.comm, found);
  if (!found.empty()) return found;
  return "non-finite energy (" + describe_fastest_node(d, state.velocity) + ")";
}

std::string format_time(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g s", seconds);
  return text;
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void StepWriter::write(State& state, double dt) {
  forces_of_this_step(model_, d_, state);  // f_int and sigma at u^n
  compute_accelerations(model_, state);    // a^n: the nodal update does not store it
  for_each_chunk(velocity_.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
    for (int c = 0; c < 3; ++c) {
      const double* v = state.velocity.component(c).data();
      const double* a = state.acceleration.component(c).data();
      double* out = velocity_.component(c).data();
      for (std::size_t i = begin; i < end; ++i) out[i] = v[i] - 0.5 * dt * a[i];
    }
  });
  for_each_chunk(von_mises_.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t e = begin; e < end; ++e) {
      material::SymTensor s;
      std::copy_n(state.stress.data() + 6 * e, 6, s.begin());
      von_mises_[e] = material::von_mises(s);
    }
  });
  gather_plastic_strain(model_, state);
  // The contact force field without the loads that ride in the same array.
  const NodalVectors* contact_force = &state.contact_force;
  if (!state.load_force.empty()) {
    contact_only_ = state.contact_force;
    add_scaled(contact_only_, -1.0, state.load_force);
    contact_force = &contact_only_;
  }
  output::StepData data;
  data.step = state.step;
  data.time = state.time;
  if (!d_.comm.distributed()) {
    data.displacement = &state.displacement;
    data.velocity = &velocity_;
    data.acceleration = &state.acceleration;
    data.contact_force = contact_force;
    data.gap = state.gap.data();
    data.stress = state.stress.data();
    data.von_mises = von_mises_.data();
    data.plastic_strain = state.plastic_strain.data();
    data.damage = state.damage.empty() ? nullptr : state.damage.data();
    data.status = state.status.empty() ? nullptr : state.status.data();
  } else {
    // The writer asks for the deck's fields only (every rank knows them: the same
    // deck), in its order on every rank; the owners' values go straight to its buffer.
    data.fill_rows = [&](input::OutputField field, double* rows) {
      using input::OutputField;
      switch (field) {
        case OutputField::displacement:
          return rows_of(d_, state.displacement, rows);
        case OutputField::velocity:
          return rows_of(d_, velocity_, rows);
        case OutputField::acceleration:
          return rows_of(d_, state.acceleration, rows);
        case OutputField::contact_force:
          return rows_of(d_, *contact_force, rows);
        case OutputField::gap:
          return rows_of(d_, state.gap.data(), 1, true, rows);
        case OutputField::stress:
          return rows_of(d_, state.stress.data(), 6, false, rows);
        case OutputField::von_mises:
          return rows_of(d_, von_mises_.data(), 1, false, rows);
        case OutputField::plastic_strain:
          return rows_of(d_, state.plastic_strain.data(), 1, false, rows);
        case OutputField::damage:
          return rows_of(d_, state.damage.data(), 1, false, rows);
        case OutputField::status:
          return rows_of(d_, state.status.data(), 1, false, rows);
      }
    };
  }
  writer_.write_step(data);
}
namespace {

output::ContactFigures contact_figures(const contact::ContactStatistics& statistics) {
  output::ContactFigures c;
  c.projections = statistics.projections;
  c.mean_iterations = statistics.projections > 0 ? static_cast<double>(statistics.iterations) /
                                                       static_cast<double>(statistics.projections)
                                                 : 0.0;
  c.max_iterations = statistics.max_iterations;
  c.not_converged = statistics.not_converged;
  c.saddle_points = statistics.saddle_points;
  c.fallbacks = statistics.fallbacks;
  c.max_penetration_over_h = statistics.max_penetration_over_h;
  c.penalty_stiffness = statistics.max_pair_stiffness;
  return c;
}

}  // namespace

void summarise_contact(const ContactModel& contact, const contact::ContactStatistics& statistics,
                       output::RunSummary& summary) {
  static_cast<output::ContactFigures&>(summary.contact) = contact_figures(statistics);
  summary.contact.pairs.resize(contact.pairs.size());
  double global_search = 0.0, local_search = 0.0, segmentation = 0.0, forces = 0.0;
  for (std::size_t k = 0; k < contact.pairs.size(); ++k) {
    const ContactPair& pair = contact.pairs[k];
    output::ContactPairSummary& out = summary.contact.pairs[k];
    out.name = pair.name;
    out.slave_points = input::name(pair.slave_points);
    out.method = std::string(contact::name(pair.settings.projection.method));
    out.figures = contact_figures(pair.statistics);
    out.local_search_seconds = pair.seconds.local_search;
    out.segmentation_seconds = pair.seconds.segmentation;
    out.max_force = pair.max_force;
    out.peak_normal_force_sum = pair.peak_normal_force_sum;
    out.points_in_contact_at_peak = pair.points_in_contact_at_peak;
    out.friction_work = 0.0;
    for (const auto& state : pair.states) out.friction_work += state.friction_work;
    global_search += pair.seconds.global_search;
    local_search += pair.seconds.local_search;
    segmentation += pair.seconds.segmentation;
    forces += pair.seconds.forces;
  }
  summary.contact.walls.resize(contact.walls.size());
  for (std::size_t k = 0; k < contact.walls.size(); ++k) {
    const RigidWall& wall = contact.walls[k];
    output::WallSummary& out = summary.contact.walls[k];
    out.name = wall.name;
    out.slave_points = wall.surfaces.quadrature ? "quadrature" : "nodes";
    out.max_force = wall.max_force;
    out.max_penetration_over_h = wall.statistics.max_penetration_over_h;
    out.penalty_stiffness = wall.statistics.max_pair_stiffness;
    out.friction_work = wall.state.friction_work;
    forces += wall.seconds.forces;
  }
  summary.phase_seconds.contact_global_search = global_search;
  summary.phase_seconds.contact_local_search = local_search;
  summary.phase_seconds.contact_segmentation = segmentation;
  summary.phase_seconds.contact_forces = forces;
}

std::string small_strain_warning(const input::Deck& deck, const Model& model, const State& state,
                                 const mpi::Communicator& comm, const std::string& when) {
  double ratio = 0.0, part = 0.0;
  for (const element::ElementBlock& block : model.blocks) {
    if (block.law.finite || block.count == 0) continue;
    const double youngs = block.material.mu * (3.0 * block.material.lambda + 2.0 * block.material.mu) /
                          (block.material.lambda + block.material.mu);
    for (std::uint32_t e = 0; e < block.count; ++e)
      for (int k = 0; k < 6; ++k) {
        const double r = std::abs(state.stress[6 * (std::size_t(block.first_element) + e) + k]) / youngs;
        if (r > ratio) ratio = r, part = double(model.mesh.element_part[block.first_element]);
      }
  }
  const double mine[2] = {ratio, part};
  const std::vector<double> all = mpi::all_gather(comm, mine, 2);
  ratio = all[0], part = all[1];
  for (std::size_t r = 1; r < all.size() / 2; ++r)
    if (all[2 * r] > ratio) ratio = all[2 * r], part = all[2 * r + 1];
  if (ratio <= 0.1) return "";
  char text[300];
  std::snprintf(text, sizeof text,
                "part %s: stress of %.3g E%s under small-strain kinematics, a strain past 10 %%: "
                "small strain reads rotations as strain; set kinematics: finite",
                deck.parts[std::size_t(part)].name.c_str(), ratio, when.c_str());
  return text;
}

double prescribed_jump_energy(const Model& model, const mpi::Communicator& comm) {
  const std::vector<double>& counted = model.counted_mass.empty() ? model.mass : model.counted_mass;
  double jump = 0.0;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = 0; k < model.fixed_velocity[c].size(); ++k) {
      const double v = model.fixed_velocity[c][k];
      jump += 2.0 * counted[model.fixed_nodes[c][k]] * v * v;
    }
  double total = 0.0;
  for (const double each : mpi::all_gather(comm, &jump, 1)) total += each;
  return total;
}

// The figures of a step summed over the ranks, in rank order (the same bits on every
// rank, so all take the same decisions): the nodal update's sums, the element
// energies (in `energy`) and the stop any rank asks for (the largest). Identity on one rank.
NodalUpdate reduce_over_ranks(const mpi::Communicator& comm, NodalUpdate update, Energies& energy,
                              std::vector<std::array<double, 3>>& reactions,
                              const std::vector<std::array<double, 3>>& reaction_errors, int signal,
                              int& stop_requested) {
  if (!comm.distributed()) {
    stop_requested = signal;
    for (std::size_t b = 0; b < reactions.size(); ++b)
      for (std::size_t c = 0; c < 3; ++c) reactions[b][c] += reaction_errors[b][c];
    return update;
  }
  constexpr std::size_t fixed = 13;
  const std::size_t n = fixed + 6 * reactions.size();
  std::vector<double> mine = {update.finite ? 0.0 : 1.0,
                              update.kinetic,
                              update.mass_acceleration_squared,
                              update.largest_component,
                              energy.internal,
                              energy.hourglass,
                              double(signal),
                              energy.plastic,
                              energy.external_work,
                              energy.eroded,
                              energy.eroded_elements,
                              update.old_power,
                              update.new_power};
  for (std::size_t b = 0; b < reactions.size(); ++b)
    for (std::size_t c = 0; c < 3; ++c) mine.insert(mine.end(), {reactions[b][c], reaction_errors[b][c]});
  const std::vector<double> all = mpi::all_gather(comm, mine.data(), int(n));
  // Each reaction: every rank's sum and compensation, added compensated in rank order:
  // the same value as one process's to a few units in its last place (add_boundary_reactions).
  for (std::size_t b = 0; b < reactions.size(); ++b)
    for (std::size_t c = 0; c < 3; ++c) {
      double sum = 0.0, error = 0.0;
      for (std::size_t r = 0; r < std::size_t(comm.size); ++r) {
        add_compensated(sum, error, all[n * r + fixed + 6 * b + 2 * c]);
        add_compensated(sum, error, all[n * r + fixed + 6 * b + 2 * c + 1]);
      }
      reactions[b][c] = sum + error;
    }
  NodalUpdate total;
  total.finite = all[0] == 0.0;
  total.kinetic = all[1];
  total.mass_acceleration_squared = all[2];
  total.largest_component = all[3];
  energy.internal = all[4];
  energy.hourglass = all[5];
  stop_requested = int(all[6]);
  energy.plastic = all[7];
  energy.external_work = all[8];
  energy.eroded = all[9];
  energy.eroded_elements = all[10];
  total.old_power = all[11];
  total.new_power = all[12];
  for (std::size_t r = 1; r < std::size_t(comm.size); ++r) {
    const double* f = all.data() + n * r;
    total.finite = total.finite && f[0] == 0.0;
    total.kinetic += f[1];
    total.mass_acceleration_squared += f[2];
    total.largest_component = std::max(total.largest_component, f[3]);
    energy.internal += f[4];
    energy.hourglass += f[5];
    stop_requested = std::max(stop_requested, int(f[6]));
    energy.plastic += f[7];
    energy.external_work += f[8];
    energy.eroded += f[9];
    energy.eroded_elements += f[10];
    total.old_power += f[11];
    total.new_power += f[12];
  }
  return total;
}

// The exchanges' figures of all ranks (summary mpi: sums, and the longest wait) and
// each rank's.
void summarise_ranks(const Decomposition& d, const ContactModel& contact, const output::PhaseSeconds& phases,
                     output::MpiSummary& out) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_mb = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss: kB on Linux
  double contact_seconds = 0.0;                             // this rank's passes
  for (const ContactPair& pair : contact.pairs)
    contact_seconds += pair.seconds.global_search + pair.seconds.local_search + pair.seconds.segmentation +
                       pair.seconds.forces;
  for (const RigidWall& wall : contact.walls)
    contact_seconds += wall.seconds.global_search + wall.seconds.local_search + wall.seconds.forces;
  if (!d.comm.distributed()) {
    output::MpiSummary::Rank one;
    one.peak_resident_mb = peak_mb;
    one.element_seconds = phases.element_forces;
    one.contact_seconds = contact_seconds;
    one.contact_nodes = double(contact.nodes.size());
    for (const ContactPair& pair : contact.pairs)
      for (const contact::ContactSurfaces& pass : pair.passes) {
        one.contact_points += double(pass.point_count());
        one.contact_segments += double(pass.segments.size());
      }
    for (const RigidWall& wall : contact.walls) one.contact_points += double(wall.surfaces.point_count());
    out.per_rank = {one};
    return;
  }
  const HaloFigures h = halo_figures(d);
  const ContactShareFigures c = contact_share_figures(d.contact);
  constexpr int n = 15;
  const double mine[n] = {double(h.shared_nodes),
                          double(h.messages_sent),
                          double(h.bytes_sent),
                          d.exchange_seconds + c.wait_seconds,
                          peak_mb,
                          double(contact.nodes.size()),
                          c.points,
                          c.segments,
                          c.ghost_segments,
                          c.ghost_nodes,
                          c.messages_per_step,
                          c.bytes_per_step,
                          c.wait_seconds,
                          phases.element_forces - d.exchange_seconds,  // the force waits are inside it
                          contact_seconds};
  const std::vector<double> all = mpi::all_gather(d.comm, mine, n);
  for (std::size_t r = 0; r < all.size() / n; ++r) {
    const double* f = all.data() + n * r;
    out.shared_nodes += long(f[0]);
    out.messages_per_step += long(f[1]);
    out.bytes_per_step += f[2];
    out.exchange_seconds = std::max(out.exchange_seconds, f[3]);
    out.contact_nodes += long(f[9]);
    out.per_rank.push_back(
        {f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11], f[1], f[2], f[3], f[13], f[14]});
  }
  out.partition = d.partitioning == Partitioning::metis ? "metis" : "bisection";
  out.weigh = d.weighed_by_work ? "work" : "elements";
  out.setup = d.set_up_by_rank ? "by_rank" : "whole";
  out.edge_cut = d.edge_cut;
}

}  // namespace exdyn::solver
