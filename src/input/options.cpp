#include "input/options.hpp"

#include "common/errors.hpp"

namespace exdyn::input {

const char* name(MaterialModel model) {
  switch (model) {
    case MaterialModel::linear_elastic:
      return "linear_elastic";
    case MaterialModel::elastic_plastic:
      return "elastic_plastic";
    case MaterialModel::johnson_cook:
      return "johnson_cook";
  }
  return "?";
}

const char* name(Kinematics kinematics) {
  switch (kinematics) {
    case Kinematics::automatic:
      return "auto";
    case Kinematics::small:
      return "small";
    case Kinematics::finite:
      return "finite";
  }
  return "?";
}

Kinematics resolved_kinematics(const PartOptions& part, const MaterialOptions& material) {
  if (part.kinematics != Kinematics::automatic) return part.kinematics;
  return material.model == MaterialModel::linear_elastic ? Kinematics::small : Kinematics::finite;
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

const char* name(PartFace side) {
  switch (side) {
    case PartFace::xmin:
      return "xmin";
    case PartFace::xmax:
      return "xmax";
    case PartFace::ymin:
      return "ymin";
    case PartFace::ymax:
      return "ymax";
    case PartFace::zmin:
      return "zmin";
    case PartFace::zmax:
      return "zmax";
    case PartFace::surface:
      return "surface";
    case PartFace::start:
      return "start";
    case PartFace::end:
      return "end";
    case PartFace::cut_x:
      return "cut_x";
    case PartFace::cut_y:
      return "cut_y";
    case PartFace::cut_z:
      return "cut_z";
  }
  return "?";
}

std::vector<PartFace> faces_of(const PartOptions& part) {
  std::vector<PartFace> faces;
  switch (part.geometry) {
    case Geometry::box:
      return {PartFace::xmin, PartFace::xmax, PartFace::ymin, PartFace::ymax, PartFace::zmin, PartFace::zmax};
    case Geometry::cylinder:
      faces = {PartFace::surface, PartFace::start, PartFace::end};
      break;
    case Geometry::sphere:
      faces = {PartFace::surface};
      break;
  }
  const std::array<PartFace, 3> cuts{PartFace::cut_x, PartFace::cut_y, PartFace::cut_z};
  for (int axis = 0; axis < 3; ++axis)
    if (part.keep[static_cast<std::size_t>(axis)] != 0) faces.push_back(cuts[static_cast<std::size_t>(axis)]);
  return faces;
}

const char* name(Geometry geometry) {
  switch (geometry) {
    case Geometry::box:
      return "box";
    case Geometry::cylinder:
      return "cylinder";
    case Geometry::sphere:
      return "sphere";
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
    case OutputField::plastic_strain:
      return "plastic_strain";
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
