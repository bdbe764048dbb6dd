#include "input/options.hpp"

#include "common/errors.hpp"

namespace exdyn::input {

const char* name(MaterialModel model) {
  switch (model) {
    case MaterialModel::linear_elastic:
      return "linear_elastic";
  }
  return "?";
}

const char* name(Formulation formulation) {
  switch (formulation) {
    case Formulation::hex8:
      return "hex8";
    case Formulation::hex8r:
      return "hex8r";
    case Formulation::hex20:
      return "hex20";
    case Formulation::hex20r:
      return "hex20r";
  }
  return "?";
}

const char* name(SlavePoints points) {
  switch (points) {
    case SlavePoints::nodes:
      return "nodes";
    case SlavePoints::quadrature:
      return "quadrature";
  }
  return "?";
}

const char* name(BoxSide side) {
  switch (side) {
    case BoxSide::xmin:
      return "xmin";
    case BoxSide::xmax:
      return "xmax";
    case BoxSide::ymin:
      return "ymin";
    case BoxSide::ymax:
      return "ymax";
    case BoxSide::zmin:
      return "zmin";
    case BoxSide::zmax:
      return "zmax";
  }
  return "?";
}

const char* name(OutputField field) {
  switch (field) {
    case OutputField::displacement:
      return "displacement";
    case OutputField::velocity:
      return "velocity";
    case OutputField::acceleration:
      return "acceleration";
    case OutputField::stress:
      return "stress";
    case OutputField::von_mises:
      return "von_mises";
    case OutputField::contact_force:
      return "contact_force";
    case OutputField::gap:
      return "gap";
  }
  return "?";
}

std::string face_name(const Deck& deck, const FaceRef& face) {
  const bool known_part = face.part >= 0 && static_cast<std::size_t>(face.part) < deck.parts.size();
  EXDYN_ASSERT(known_part);
  const std::string part =
      known_part ? deck.parts[static_cast<std::size_t>(face.part)].name : "part#" + std::to_string(face.part);
  return part + "." + name(face.side);
}

}  // namespace exdyn::input
