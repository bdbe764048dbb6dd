// The time step of the loop (step_clock.hpp).
#include "solver/step_clock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/mpi.hpp"

namespace exdyn::solver {

StepClock::StepClock(const input::TimeOptions& time, double critical_dt, const Model& model,
                     const mpi::Communicator* spread) {
  const TimeStepping fixed = time_stepping(time, critical_dt);
  end_time_ = time.end_time;
  courant_ = time.courant;
  min_ratio_ = time.min_dt_ratio;
  follows_ = !time.dt && std::any_of(model.blocks.begin(), model.blocks.end(),
                                     [](const element::ElementBlock& b) { return b.law.finite; });
  previous_ = next_ = first_ = smallest_ = uncut_ = fixed.dt;
  planned_ = fixed.steps;
  fixed_part_ = std::numeric_limits<double>::infinity();
  for (const element::ElementBlock& block : model.blocks)
    if (!block.law.finite)
      fixed_part_ = std::min(fixed_part_, element::critical_time_step(block, model.mesh.x_ref));
  if (spread != nullptr && spread->distributed()) {  // the whole model's: an exact minimum and "any"
    double figures[2] = {fixed_part_, follows_ ? -1.0 : 0.0};
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, figures, 2, MPI_DOUBLE, MPI_MIN, spread->comm),
               "MPI_Allreduce of the stable step");
    fixed_part_ = figures[0];
    follows_ = figures[1] < 0.0;
  }
}

bool StepClock::last(long step) const {
  if (!follows_) return step == planned_;
  return time_ >= end_time_ - 1e-9 * first_;
}

std::string StepClock::plan(long step, const Decomposition& d, element::CurrentStep finite) {
  if (!follows_) return {};
  double stable = fixed_part_;
  std::uint32_t element = 0;
  if (finite.dt < stable) stable = finite.dt, element = global_element_id(d, finite.element);
  // The smallest over the ranks (ties: the lowest element), the same on every rank.
  const double mine[2] = {stable, double(element)};
  const std::vector<double> all = mpi::all_gather(d.comm, mine, 2);
  stable = all[0], element = std::uint32_t(all[1]);
  for (std::size_t r = 1; r < all.size() / 2; ++r)
    if (all[2 * r] < stable || (all[2 * r] == stable && all[2 * r + 1] < element))
      stable = all[2 * r], element = std::uint32_t(all[2 * r + 1]);
  next_ = courant_ * stable;
  if (step == 0) {
    first_ = previous_ = smallest_ = next_;
    planned_ = std::max(1L, long(std::ceil(end_time_ / first_ - 1e-9)));
  }
  smallest_ = std::min(smallest_, next_);
  if (next_ < min_ratio_ * first_) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "the time step fell to %.3g s, below time.min_dt_ratio = %.3g of the first step %.3g s: "
                  "element %u is crushed (its stable step is the smallest)",
                  next_, min_ratio_, first_, element);
    return text;
  }
  uncut_ = next_;
  next_ = std::min(next_, std::max(end_time_ - time_, 0.0));  // land on end_time
  return {};
}

void StepClock::restore(const Saved& s) {
  time_ = s.time, previous_ = s.previous, next_ = s.next, first_ = s.first, smallest_ = s.smallest,
  uncut_ = s.uncut;
  if (follows_) planned_ = std::max(1L, long(std::ceil(end_time_ / first_ - 1e-9)));
}

void StepClock::advance(long step) {
  if (!follows_) {
    time_ = double(step + 1) * next_;  // t^n = n dt: the bits of a fixed step
    return;
  }
  time_ += next_;
  previous_ = next_;
}

}  // namespace exdyn::solver
