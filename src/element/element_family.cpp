// The registry of element families: one line per formulation.
#include "element/element_family.hpp"

namespace exdyn::element {

const ElementFamily& element_family(input::Formulation formulation) {
  switch (formulation) {
    case input::Formulation::hex8:
      return hex8_family;
    case input::Formulation::hex8r:
      return hex8r_family;
    case input::Formulation::hex20:
      return hex20_family;
    case input::Formulation::hex20r:
      return hex20r_family;
  }
  return hex8_family;
}

}  // namespace exdyn::element
