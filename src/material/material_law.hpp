// A part's material law, chosen once when its element block is built: the elastic
// constants (every model's, and the wave speed), the flow rule of a plastic model
// (elastic_plastic.hpp, johnson_cook.hpp) and the kinematics it runs under (j2.hpp).
// The element families pick their loop from it once (element/constitutive.hpp);
// nothing inside a loop asks which model it runs.
#pragma once

#include "input/options.hpp"
#include "material/elastic.hpp"
#include "material/elastic_plastic.hpp"
#include "material/failure.hpp"
#include "material/j2.hpp"
#include "material/johnson_cook.hpp"

namespace exdyn::material {

enum class FlowRule { none, hardening, johnson_cook };

struct MaterialLaw {
  FlowRule flow = FlowRule::none;
  Hardening hardening;       // flow == hardening
  JohnsonCook johnson_cook;  // flow == johnson_cook
  NoYield no_yield;          // flow == none
  bool finite = false;       // large deformation (j2.hpp, update_finite)
  // hex8 under finite kinematics: F-bar (the element's mean volume ratio in the
  // volumetric response), against the volumetric locking of plastic flow.
  bool f_bar = true;
  Failure failure;  // damage and erosion (none: the material never breaks)

  // The small-strain linear elastic law of the fast kernels (no state, no law call).
  bool linear_small() const { return flow == FlowRule::none && !finite; }
  // Doubles of state per integration point.
  int state_size() const { return flow == FlowRule::none ? 0 : j2_state_size; }
};

inline MaterialLaw make_law(const input::MaterialOptions& options, input::Kinematics kinematics,
                            bool f_bar = true) {
  MaterialLaw law;
  law.finite = kinematics == input::Kinematics::finite;
  law.f_bar = f_bar;
  law.failure = make_failure(options);
  switch (options.model) {
    case input::MaterialModel::linear_elastic:
      break;
    case input::MaterialModel::elastic_plastic:
      law.flow = FlowRule::hardening;
      law.hardening = options.hardening.empty()
                          ? Hardening::linear(options.yield_stress, options.hardening_modulus)
                          : Hardening::table(options.hardening);
      break;
    case input::MaterialModel::johnson_cook:
      law.flow = FlowRule::johnson_cook;
      law.johnson_cook = {options.jc_a, options.jc_b, options.jc_n, options.jc_c,
                          options.reference_strain_rate};
      if (const auto& t = options.thermal_softening) {
        law.johnson_cook.heating = t->taylor_quinney / (options.density * t->specific_heat *
                                                        (t->melting_temperature - t->room_temperature));
        law.johnson_cook.m = t->m;
      }
      break;
  }
  return law;
}

}  // namespace exdyn::material
