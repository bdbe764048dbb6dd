// The deck, parsed: plain option structs with every default filled in.
// Only input/deck_reader.cpp touches YAML; physics code sees these structs.
// Every key of ../shared/spec/input-deck.md maps to one field here
// (docs/input.md documents each).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contact/search_names.hpp"

namespace exdyn::input {

using Vec3 = std::array<double, 3>;

// linear_elastic: isotropic elasticity; elastic_plastic: von Mises with isotropic
// hardening, linear or tabulated; johnson_cook: von Mises with the Johnson-Cook flow
// stress without temperature (docs/theory.md, "Materials").
enum class MaterialModel { linear_elastic, elastic_plastic, johnson_cook };
enum class FailureModel { none, plastic_strain, johnson_cook };
// Where the Johnson-Cook failure strain is used (docs/theory.md, "Damage and erosion"):
// no damage at a triaxiality below -1/3, eps_f held at its value at 1.5 above 1.5, and
// the rate ratio held at 1e12 above it. A deck's D values must give eps_f > 0 there.
inline constexpr double failure_triaxiality_min = -1.0 / 3.0;
inline constexpr double failure_triaxiality_max = 1.5;
inline constexpr double failure_rate_ratio_max = 1.0e12;

// johnson_cook's thermal softening: sigma_y times (1 - T*^m), T* = (T - T_r) / (T_m - T_r),
// the temperature adiabatic, T = T_r + chi W_p / (rho c_p) (docs/theory.md, "Materials").
struct ThermalSoftening {
  double m = 1.0;                  // the exponent, > 0
  double melting_temperature = 0;  // T_m, K, > room_temperature
  double room_temperature = 293;   // T_r, K, >= 0
  double specific_heat = 0;        // c_p, J/(kg K), > 0
  double taylor_quinney = 0.9;     // chi, the share of plastic work that heats, in [0, 1]

  bool operator==(const ThermalSoftening&) const = default;
};

struct MaterialOptions {
  std::string name;
  MaterialModel model = MaterialModel::linear_elastic;
  double density = 0.0;         // rho > 0, mass per volume
  double youngs_modulus = 0.0;  // E > 0, force per area
  double poissons_ratio = 0.0;  // nu in (-1, 0.5)
  // elastic_plastic: sigma_y = yield_stress + hardening_modulus eps_p, or the table
  // `hardening` (eps_p, sigma_y) rows when given (then yield_stress is its first sigma_y).
  double yield_stress = 0.0;                     // sigma_y0 > 0, force per area
  double hardening_modulus = 0.0;                // H >= 0, force per area
  std::vector<std::array<double, 2>> hardening;  // [[0, sigma_y0], [eps_p, sigma_y], ...]
  // johnson_cook: sigma_y = (A + B eps_p^n)(1 + C ln(max(eps_dot_p / eps_dot_0, 1))).
  double jc_a = 0.0;                                  // A > 0, force per area
  double jc_b = 0.0;                                  // B >= 0, force per area
  double jc_n = 1.0;                                  // n > 0
  double jc_c = 0.0;                                  // C >= 0
  double reference_strain_rate = 1.0;                 // eps_dot_0 > 0, 1/s
  std::optional<ThermalSoftening> thermal_softening;  // johnson_cook only; none: no temperature
  // failure (elastic_plastic, johnson_cook): none, {plastic_strain: eps_f} or
  // {johnson_cook: {D1, D2, D3, D4, D5}} (docs/theory.md, "Damage and erosion").
  FailureModel failure = FailureModel::none;
  double failure_strain = 0.0;        // eps_f > 0 of plastic_strain
  std::array<double, 5> failure_d{};  // D1 .. D5 of johnson_cook (D5, temperature: kept, not used)

  bool operator==(const MaterialOptions&) const = default;
};

enum class Formulation {
  hex8,    // 8-node brick, 2x2x2 Gauss points
  hex8r,   // 8-node brick, one point, hourglass stiffness (HourglassModel)
  hex20,   // 20-node serendipity brick, 3x3x3 Gauss points
  hex20r,  // 20-node serendipity brick, 2x2x2 Gauss points
};

// The 20-node formulations: their parts get mid-edge nodes and 8-node face segments.
constexpr bool is_quadratic(Formulation formulation) {
  return formulation == Formulation::hex20 || formulation == Formulation::hex20r;
}

// The shape of a part (docs/input.md): a box, a mapped cylinder or ball, or the
// hexahedra of a physical volume of a Gmsh mesh file.
enum class Geometry { box, cylinder, sphere, mesh };

// `mesh: {file, volume, reorder}`: a part read from a Gmsh mesh file.
struct MeshFileOptions {
  // The file: `file` of the deck resolved against the deck's folder, absolute, so that the
  // echo of `exdyn check` reads the same file from anywhere.
  std::string path;
  std::string volume;                 // the physical volume's name
  std::vector<std::string> surfaces;  // the file's physical surfaces (read with the deck)
  // Number elements along a space-filling curve and nodes by first use (mesh/imported.hpp);
  // false keeps the file's order.
  bool reorder = true;

  bool operator==(const MeshFileOptions&) const = default;
};

// How hex8r resists its hourglass modes (docs/theory.md, "hex8r"): the assumed-strain
// stiffness of each mode and direction from the strain field it is in a rectangular
// brick, perfectly plastic at the flow stress in a plastic material (coefficient 1 is
// physical); or Flanagan-Belytschko's one isotropic, elastic stiffness (coefficient
// 0.05 by default there).
enum class HourglassModel { assumed_strain, flanagan_belytschko };

// A part's hourglass control as the element blocks take it. A bare number is a
// Flanagan-Belytschko coefficient, as a deck's `coefficient` without `model`.
struct HourglassControl {
  HourglassModel model = HourglassModel::assumed_strain;
  double coefficient = 1.0;
  HourglassControl() = default;
  HourglassControl(HourglassModel m, double c) : model(m), coefficient(c) {}
  HourglassControl(double flanagan_belytschko)  // NOLINT(google-explicit-constructor): a number is FB's
      : model(HourglassModel::flanagan_belytschko), coefficient(flanagan_belytschko) {}
};

// How a part's strains are measured (docs/theory.md, "Finite strain"): small strain on
// the reference configuration, or large deformation (total Lagrangian, hyperelastic-
// plastic); automatic: finite for a plastic material, small for linear_elastic.
enum class Kinematics { automatic, small, finite };

struct PartOptions {
  std::string name;
  Geometry geometry = Geometry::box;
  Vec3 box_min{};  // box
  Vec3 box_max{};
  // cylinder and sphere: the centre (a cylinder's axis starts there), radius R (m); a
  // cylinder's axis (0 x, 1 y, 2 z) and length L (m).
  Vec3 center{};
  double radius = 0.0;
  int axis = 2;
  double length = 0.0;
  // `keep`: for each axis, 0 both halves, +1 the half-space >= centre, -1 <= centre.
  std::array<int, 3> keep{};
  // box: nx, ny, nz; cylinder: n_around (a quarter circumference), n_radius, n_axis;
  // sphere: n_around (a quarter of the equator), n_radius, and 0. Each >= 1.
  std::array<int, 3> elements{};
  // Ratio of the last element's size to the first's along each count (box: x, y, z;
  // cylinder: around, radius (towards the surface), axis; sphere: around, radius, -).
  std::array<double, 3> grading{1.0, 1.0, 1.0};
  std::string material;     // a key of `materials`
  int material_index = -1;  // index into Deck::materials
  Formulation formulation = Formulation::hex8;
  // hex8 and hex8r only (an error on a 20-node part). A deck that gives `coefficient`
  // without `model` gets Flanagan-Belytschko, the meaning the key had before `model`.
  HourglassModel hourglass_model = HourglassModel::assumed_strain;
  double hourglass_coefficient = 1.0;
  Vec3 initial_velocity{};
  // initial_angular_velocity: omega x (x - axis_point) is added to each node's velocity.
  std::optional<std::array<Vec3, 2>> initial_angular_velocity;  // {axis_point (m), omega (rad/s)}
  Kinematics kinematics = Kinematics::automatic;
  // hex8 under finite kinematics: F-bar against volumetric locking (false: plain 2x2x2,
  // which locks in plastic flow; kept to measure it).
  bool f_bar = true;
  // Random distortion of the structured grid (docs/input.md, mesh/mesh.hpp): interior
  // nodes move by up to fraction x h per component; 0 = the regular grid.
  double perturbation_fraction = 0.0;  // in [0, 0.5)
  unsigned perturbation_seed = 1;
  MeshFileOptions mesh;  // Geometry::mesh

  bool operator==(const PartOptions&) const = default;
};

// The named faces of a part: a box's six sides; a cylinder's curved side (surface) and its
// flat ends (start, end); a ball's surface; the flat face a `keep` cut leaves (cut_x ...);
// a mesh part's whole boundary (surface) and its physical surfaces (physical). Not named
// in a deck: interior, the faces a part's bricks share that erosion can open
// (mesh/interior_faces.hpp), FaceRef::surface the bricks' local face.
enum class PartFace {
  xmin,
  xmax,
  ymin,
  ymax,
  zmin,
  zmax,
  surface,
  start,
  end,
  cut_x,
  cut_y,
  cut_z,
  physical,
  interior
};

// A named face `<part>.<side>`.
struct FaceRef {
  int part = -1;  // index into Deck::parts
  PartFace side = PartFace::xmin;
  int surface = -1;  // physical: index into the part's mesh.surfaces
  // A side of the face between its folds (mesh::FaceSides): set by the model for a
  // single surface, which takes each side as a face; -1: the whole face.
  int fold_side = -1;

  bool operator==(const FaceRef&) const = default;
};

// `fix: [x]` is `velocity: {x: 0}`: a component of the faces' nodes' velocity held at
// a constant value from the start (a prescribed motion).
struct BoundaryConditionOptions {
  std::vector<FaceRef> faces;
  std::array<bool, 3> fix{false, false, false};   // x, y, z: the velocity component is prescribed
  std::array<double, 3> velocity{0.0, 0.0, 0.0};  // its value where fix, m/s (0: held at rest)
  bool moving() const { return velocity[0] != 0.0 || velocity[1] != 0.0 || velocity[2] != 0.0; }

  bool operator==(const BoundaryConditionOptions&) const = default;
};

struct PenaltyOptions {
  // Exactly one of the two: automatic rule times `scale`, or a fixed stiffness.
  double scale = 1.0;
  std::optional<double> stiffness;  // force per length (nodes) or pressure per length (quadrature)
  double damping = 0.2;             // viscous contact damping, fraction of critical (docs/input.md)

  bool operator==(const PenaltyOptions&) const = default;
};

struct GlobalSearchOptions {
  std::optional<double> cell_size;  // bucket cell edge (length); unset = automatic

  bool operator==(const GlobalSearchOptions&) const = default;
};

struct LocalSearchOptions {
  contact::SearchMethod method = contact::SearchMethod::bfgs;
  double tolerance = 1.0e-10;  // stop when |step in (xi1, xi2)| <= tolerance
  int max_iterations = 100;
  contact::InitialGuess initial_guess = contact::InitialGuess::lsp;
  // The method that settles a projection `method` failed on (not converged, a saddle or a
  // maximum) before the point is dropped; unset (`none`): the method alone.
  std::optional<contact::SearchMethod> fallback = contact::SearchMethod::robust;

  bool operator==(const LocalSearchOptions&) const = default;
};

// The largest number of Gauss points per direction of a slave segment.
inline constexpr int max_quadrature = 6;

// What of the slave side is projected onto the master segments.
enum class SlavePoints {
  automatic,   // `auto`: quadrature on 8-node slave segments, nodes on 4-node ones
  nodes,       // each slave node
  quadrature,  // each Gauss point of each slave segment (pre-discretization penalty)
  mortar,      // segment to segment: the Gauss points of the pieces where slave and master overlap
};

// The points of a triangle rule on each piece of a mortar segmentation: 1, 3, 6 or 7
// (exact to degree 1, 2, 4, 5). By default the least that integrates the consistent
// forces of a uniform pressure on flat faces exactly on both sides: the shape functions
// are of degree 2 on 4-node segments (3 points) and 3 on 8-node ones (6 points).
inline constexpr std::array<int, 4> mortar_triangle_points{1, 3, 6, 7};
constexpr int mortar_default_triangle_points(bool eight_node_segments) { return eight_node_segments ? 6 : 3; }

// Coulomb friction (docs/contact.md, "Friction"): mu = mu_d + (mu_s - mu_d) exp(-d |v_slip|).
struct FrictionOptions {
  double static_coefficient = 0.0;   // mu_s >= mu_d
  double dynamic_coefficient = 0.0;  // mu_d >= 0
  double decay = 0.0;                // d >= 0, s/m

  bool operator==(const FrictionOptions&) const = default;
};

struct ContactOptions {
  std::string name;
  std::vector<FaceRef> slave;
  std::vector<FaceRef> master;
  bool two_pass = true;
  // `surface`: single-surface contact, slave and master the same faces (one pass, each
  // point against the segments that share no node with it); surface_all: `surface: all`,
  // the faces every part's exterior (exterior_faces).
  bool single_surface = false;
  bool surface_all = false;
  SlavePoints slave_points = SlavePoints::automatic;
  // Gauss points per direction on each slave segment (slave_points: quadrature),
  // 1 to max_quadrature; unset: 2 on 4-node and 3 on 8-node segments. With
  // slave_points: mortar, the points of the rule on each triangle of a piece
  // (mortar_triangle_points); unset: 3 where both sides have 4-node segments, else 6.
  std::optional<int> quadrature;
  PenaltyOptions penalty;
  GlobalSearchOptions search;
  LocalSearchOptions local_search;
  std::optional<FrictionOptions> friction;  // unset: frictionless

  bool operator==(const ContactOptions&) const = default;
};

// A flat rigid wall (docs/contact.md, "Rigid walls"): the slave points of the listed
// faces stay on the side the normal points to.
struct RigidWallOptions {
  std::string name;
  Vec3 point{};   // a point of the plane at t = 0, m
  Vec3 normal{};  // towards the bodies' side, any length > 0
  std::vector<FaceRef> slave;
  SlavePoints slave_points = SlavePoints::automatic;
  std::optional<FrictionOptions> friction;
  Vec3 velocity{};  // the wall's constant velocity, m/s

  bool operator==(const RigidWallOptions&) const = default;
};

// A body force rho g per unit volume on the listed parts (empty: every part).
struct LoadOptions {
  Vec3 gravity{};          // m/s^2
  std::vector<int> parts;  // indices into Deck::parts

  bool operator==(const LoadOptions&) const = default;
};

struct TimeOptions {
  double end_time = 0.0;
  double courant = 0.9;      // used when dt is not given
  std::optional<double> dt;  // fixed step; exclusive with an explicit courant
  // With courant and finite-strain parts the step follows the deformed elements; a run
  // whose step falls below this fraction of its first step stops (exit 1).
  double min_dt_ratio = 1.0e-3;  // in (0, 1)
  // An element of a part that can fail whose own step falls below min_dt_ratio of the
  // first step, or that inverts, fails and is eroded instead of stopping the run.
  bool erode = false;

  bool operator==(const TimeOptions&) const = default;
};

enum class OutputField {
  displacement,
  velocity,
  acceleration,
  stress,
  von_mises,
  contact_force,
  gap,
  plastic_strain,
  damage,  // per element: D of a failing material (0 elsewhere)
  status   // per element: 1 alive, 0 eroded
};

inline constexpr std::array<OutputField, 10> all_output_fields{
    OutputField::displacement, OutputField::velocity,       OutputField::acceleration,
    OutputField::stress,       OutputField::von_mises,      OutputField::contact_force,
    OutputField::gap,          OutputField::plastic_strain, OutputField::damage,
    OutputField::status};
// The fields written when the deck lists none: all but damage and status, which join
// them when a material can fail (deck_validator.cpp).
inline constexpr std::array<OutputField, 8> default_output_fields{
    OutputField::displacement, OutputField::velocity,      OutputField::acceleration,
    OutputField::stress,       OutputField::von_mises,     OutputField::contact_force,
    OutputField::gap,          OutputField::plastic_strain};

struct OutputOptions {
  std::string directory = "results";
  int every = 100;  // steps between field outputs (first and last always written)
  std::vector<OutputField> fields{default_output_fields.begin(), default_output_fields.end()};
  int history_every = 1;  // steps between energy history rows
  // Written by a thread of the writer's own while the time loop goes on (docs/output.md).
  bool background = true;

  bool operator==(const OutputOptions&) const = default;
};

// Run-time guards (docs/stability.md): a run stops with a RunFailure when one fires.
// Non-finite values and inverted elements are always checked.
struct GuardOptions {
  // Total energy E^n - E^0 beyond this fraction of the largest energy seen: the
  // signature of an explicit instability (a stable elastic run stays near 1e-13).
  double energy_growth = 0.25;
  // Contact penetration beyond this fraction of h (the slave element's length
  // normal to its face); the contact search itself looks no deeper than h / 2.
  double max_penetration = 0.25;

  bool operator==(const GuardOptions&) const = default;
};

// Every struct compares member by member, so that a test can check that reading
// to_yaml(deck) back gives the same deck.
// Restart checkpoints (docs/output.md, "Checkpoints"): written when either rule is
// given; a stop on request writes one all the same.
struct CheckpointOptions {
  int every = 0;               // steps between checkpoints; 0: not by steps
  double every_seconds = 0.0;  // wall seconds between checkpoints; 0: not by time
  int keep = 2;                // the newest checkpoints kept on disk
  bool enabled() const { return every > 0 || every_seconds > 0.0; }

  bool operator==(const CheckpointOptions&) const = default;
};

struct Deck {
  std::string source_file;  // path the deck was read from
  std::string name;
  std::vector<MaterialOptions> materials;  // in file order
  std::vector<PartOptions> parts;
  std::vector<BoundaryConditionOptions> boundary_conditions;
  std::vector<ContactOptions> contact;
  std::vector<RigidWallOptions> rigid_walls;
  std::vector<LoadOptions> loads;
  TimeOptions time;
  OutputOptions output;
  GuardOptions guards;
  CheckpointOptions checkpoint;

  bool operator==(const Deck&) const = default;
};

// Names as they appear in a deck, for messages and the `check` echo.
const char* name(MaterialModel model);
const char* name(Formulation formulation);
const char* name(Kinematics kinematics);
const char* name(HourglassModel model);
// A part's kinematics with `automatic` resolved by its material.
Kinematics resolved_kinematics(const PartOptions& part, const MaterialOptions& material);
const char* name(SlavePoints points);
// `auto` resolved by the slave segments: quadrature if any has 8 nodes.
SlavePoints resolved_slave_points(SlavePoints points, bool eight_node_segments);
const char* name(PartFace side);
const char* name(Geometry geometry);
// The face names a part has: a box's six sides; cylinder: surface, start, end; sphere:
// surface; and cut_x, cut_y, cut_z for each axis `keep` cuts.
std::vector<PartFace> faces_of(const PartOptions& part);
const char* name(OutputField field);
// "<part>.<side>"
std::string face_name(const Deck& deck, const FaceRef& face);

// `surface: all`: every face of every part (faces_of), less those on a symmetry plane or
// a support: a flat face whose nodes a boundary condition holds normal to it (nothing
// can reach it from outside).
std::vector<FaceRef> exterior_faces(const Deck& deck);
// Whether `surface: all` pair `pair` follows erosion: a part among its faces can fail
// (docs/contact.md, "Faces that erosion opens").
bool follows_erosion(const Deck& deck, const ContactOptions& pair);
// The face names of a part after "<part>.": faces_of(part), then a mesh part's physical surfaces.
std::vector<std::string> side_names(const PartOptions& part);
// What a valid deck asks for that gives a poor answer (printed by `exdyn check` and
// `exdyn run`): slave_points: nodes on the 8-node segments of 20-node parts.
std::vector<std::string> deck_warnings(const Deck& deck);

}  // namespace exdyn::input
