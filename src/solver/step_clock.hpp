// The time step of the loop (docs/theory.md, "Time step"). Fixed: the deck's dt, or
// courant times the reference mesh's stable step, t^n = n dt. Following the
// deformation (courant with finite-strain parts): at every step n the stable step of
// the current configuration x^n sets dt^{n+1/2}, and central differences with
// unequal steps advance
//   v^{n+1/2} = v^{n-1/2} + (dt^{n-1/2} + dt^{n+1/2}) / 2 a^n,  u^{n+1} = u^n + dt^{n+1/2} v^{n+1/2},
// with the last step cut to land on end_time.
#pragma once

#include <cstdint>
#include <string>

#include "input/options.hpp"
#include "model/model.hpp"
#include "ranks/ranks.hpp"

namespace exdyn::solver {

class StepClock {
 public:
  // critical_dt: the reference mesh's stable step without the Courant factor, s.
  // spread: the ranks over which `model` is spread when each holds only its part of
  // it (rank_setup.hpp); null when `model` is the whole model.
  StepClock(const input::TimeOptions& time, double critical_dt, const Model& model,
            const mpi::Communicator* spread = nullptr);

  bool follows_deformation() const { return follows_; }
  double time() const { return time_; }          // t^n, s
  double previous() const { return previous_; }  // dt^{n-1/2} = t^n - t^{n-1}, s
  double next() const { return next_; }          // dt^{n+1/2}, s
  double first() const { return first_; }        // dt^{1/2}, s
  double smallest() const { return smallest_; }  // the smallest step so far, s
  // The last planned step before the cut that lands on end_time: the mesh's, s.
  double uncut() const { return uncut_; }
  // The step of the velocity update at step n: dt^{1/2} at step 0 (from v^0), else the
  // mean of the two half steps (dt itself with a fixed step: the same bits).
  double velocity_step(long step) const { return step == 0 ? next_ : 0.5 * (previous_ + next_); }
  // Steps to end_time: exact with a fixed step, an estimate at the first step otherwise.
  long planned_steps() const { return planned_; }
  bool last(long step) const;

  // dt^{n+1/2} at step n from the current configuration x^n: `finite`, the smallest
  // stable step of this rank's finite-strain blocks there (element::current_time_step,
  // local element index; infinite when none). Every rank calls it. Returns an empty
  // text, or the message of a step that fell below min_dt_ratio of the first.
  std::string plan(long step, const Decomposition& d, element::CurrentStep finite);
  // t^{n+1} = t^n + dt^{n+1/2}.
  void advance(long step);

  // What a checkpoint keeps of the clock (checkpoint.cpp), and putting it back: with a
  // step that follows the deformation, the steps planned to end_time (which a restart
  // may change) are counted again from the first step, as at step 0.
  struct Saved {
    double time = 0.0, previous = 0.0, next = 0.0, first = 0.0, smallest = 0.0, uncut = 0.0;
  };
  Saved saved() const { return {time_, previous_, next_, first_, smallest_, uncut_}; }
  void restore(const Saved& s);

 private:
  double end_time_ = 0.0, courant_ = 0.0, min_ratio_ = 0.0;
  double fixed_part_ = 0.0;  // the stable step of the small-strain blocks, s (no Courant)
  bool follows_ = false;
  double time_ = 0.0, previous_ = 0.0, next_ = 0.0, first_ = 0.0, smallest_ = 0.0, uncut_ = 0.0;
  long planned_ = 0;
};

}  // namespace exdyn::solver
