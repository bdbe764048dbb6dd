#include "input/options.hpp"

#include <algorithm>

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

const char* name(HourglassModel model) {
  switch (model) {
    case HourglassModel::assumed_strain:
      return "assumed_strain";
    case HourglassModel::flanagan_belytschko:
      return "flanagan_belytschko";
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
    case SlavePoints::automatic:
      return "auto";
    case SlavePoints::nodes:
      return "nodes";
    case SlavePoints::quadrature:
      return "quadrature";
    case SlavePoints::mortar:
      return "mortar";
  }
  return "?";
}

SlavePoints resolved_slave_points(SlavePoints points, bool eight_node_segments) {
  if (points != SlavePoints::automatic) return points;
  return eight_node_segments ? SlavePoints::quadrature : SlavePoints::nodes;
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
    case PartFace::physical:
      return "physical";
    case PartFace::interior:
      return "interior";
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
    case Geometry::mesh:
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
    case Geometry::mesh:
      return "mesh";
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
    case OutputField::damage:
      return "damage";
    case OutputField::status:
      return "status";
  }
  return "?";
}

std::string face_name(const Deck& deck, const FaceRef& face) {
  const bool known_part = face.part >= 0 && static_cast<std::size_t>(face.part) < deck.parts.size();
  EXDYN_ASSERT(known_part);
  const std::string part =
      known_part ? deck.parts[static_cast<std::size_t>(face.part)].name : "part#" + std::to_string(face.part);
  if (face.side == PartFace::physical && known_part)
    return part + "." +
           deck.parts[static_cast<std::size_t>(face.part)].mesh.surfaces.at(std::size_t(face.surface));
  if (face.side == PartFace::interior) return part + ".interior" + std::to_string(face.surface);
  return part + "." + name(face.side);
}

namespace {

// The axis a flat face of a part is normal to (0 x, 1 y, 2 z), or -1 (curved, or a mesh's).
int flat_face_axis(const PartOptions& part, PartFace side) {
  switch (side) {
    case PartFace::xmin:
    case PartFace::xmax:
    case PartFace::cut_x:
      return 0;
    case PartFace::ymin:
    case PartFace::ymax:
    case PartFace::cut_y:
      return 1;
    case PartFace::zmin:
    case PartFace::zmax:
    case PartFace::cut_z:
      return 2;
    case PartFace::start:
    case PartFace::end:
      return part.axis;
    case PartFace::surface:
    case PartFace::physical:
    case PartFace::interior:
      return -1;
  }
  return -1;
}

}  // namespace

std::vector<FaceRef> exterior_faces(const Deck& deck) {
  std::vector<FaceRef> faces;
  for (std::size_t p = 0; p < deck.parts.size(); ++p) {
    const PartOptions& part = deck.parts[p];
    for (PartFace side : faces_of(part)) {
      const FaceRef face{static_cast<int>(p), side};
      const int axis = flat_face_axis(part, side);
      const bool held =
          axis >= 0 && std::any_of(deck.boundary_conditions.begin(), deck.boundary_conditions.end(),
                                   [&](const auto& condition) {
                                     return condition.fix[std::size_t(axis)] &&
                                            condition.velocity[std::size_t(axis)] == 0.0 &&
                                            std::find(condition.faces.begin(), condition.faces.end(), face) !=
                                                condition.faces.end();
                                   });
      if (!held) faces.push_back(face);
    }
  }
  return faces;
}

bool follows_erosion(const Deck& deck, const ContactOptions& pair) {
  return pair.surface_all && std::any_of(pair.slave.begin(), pair.slave.end(), [&](const FaceRef& face) {
           const PartOptions& part = deck.parts[std::size_t(face.part)];
           return deck.materials[std::size_t(part.material_index)].failure != FailureModel::none;
         });
}

std::vector<std::string> side_names(const PartOptions& part) {
  std::vector<std::string> names;
  for (const PartFace side : faces_of(part)) names.emplace_back(name(side));
  if (part.geometry == Geometry::mesh)
    names.insert(names.end(), part.mesh.surfaces.begin(), part.mesh.surfaces.end());
  return names;
}

// A quad8 face cannot carry a uniform pressure on its nodes alone: the consistent
// nodal forces of a uniform pressure are -1/12 of the total at each corner and 1/3 at
// each mid-side node, and a node-to-segment spring can only push. Measured on the
// hex20 plate impact (docs/verification.md): the contact face's stress 2.3 % off the
// reference with nodes, 0.15 % with quadrature points.
std::vector<std::string> deck_warnings(const Deck& deck) {
  std::vector<std::string> warnings;
  auto check = [&](const std::string& what, SlavePoints points, const std::vector<FaceRef>& faces) {
    if (points != SlavePoints::nodes) return;
    for (const FaceRef& face : faces)
      if (is_quadratic(deck.parts[std::size_t(face.part)].formulation)) {
        warnings.push_back(
            what + ": slave_points: nodes on the 8-node segments of " + face_name(deck, face) +
            " (a 20-node part): a node-to-segment spring cannot give a quad8 face the negative corner "
            "forces of a uniform pressure, so the contact stresses come out wrong by a few percent near the "
            "face (the hex20 plate impact: 2.3 % at the contact face) and a symmetric scene loses its "
            "symmetry; use slave_points: auto or quadrature");
        return;
      }
  };
  for (const ContactOptions& pair : deck.contact) {
    check("contact pair " + pair.name, pair.slave_points, pair.slave);
    if (pair.two_pass && !pair.single_surface)
      check("contact pair " + pair.name + " (second pass)", pair.slave_points, pair.master);
  }
  for (const RigidWallOptions& wall : deck.rigid_walls)
    check("rigid wall " + wall.name, wall.slave_points, wall.slave);
  // Erosion and contact: a named pair keeps its faces as they were; `surface: all`
  // follows erosion (docs/contact.md, "Faces that erosion opens").
  for (const ContactOptions& pair : deck.contact) {
    if (pair.surface_all) continue;
    std::vector<FaceRef> faces = pair.slave;
    faces.insert(faces.end(), pair.master.begin(), pair.master.end());
    for (const FaceRef& face : faces) {
      const PartOptions& part = deck.parts[std::size_t(face.part)];
      if (deck.materials[std::size_t(part.material_index)].failure == FailureModel::none) continue;
      warnings.push_back(
          "contact pair " + pair.name + ": part " + part.name +
          " can fail; a named pair keeps its eroded elements' faces and never takes the faces "
          "erosion exposes: use `surface: all` (docs/contact.md, \"Faces that erosion opens\")");
      break;
    }
  }
  return warnings;
}

}  // namespace exdyn::input
