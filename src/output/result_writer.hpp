// Results on disk (../shared/spec/output.md): NAME.h5 (mesh once, one group per
// written step, energy history) and NAME.xmf (XDMF 3 temporal collection).
// After every step the HDF5 file is closed and the .xmf replaced atomically
// (temporary file + rename), so a reader never sees a step that is not on disk.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "input/options.hpp"

namespace exdyn::output {

struct MeshView {
  const NodalVectors* x_ref = nullptr;                       // N reference node coordinates
  const std::vector<std::uint32_t>* connectivity = nullptr;  // the elements' nodes one after the other,
                                                             // VTK (quadratic) hexahedron order
  const std::vector<std::int32_t>* element_part = nullptr;   // E; null = one part, index 0
  const std::vector<std::uint8_t>* element_nodes = nullptr;  // E node counts (8 or 20); null = all 8
};

// On many ranks (docs/parallel.md): the ranks that write the file together, the
// mesh's size, and the rows of the mesh and of the step fields this one writes
// (nodes [node_begin, node_end), elements [element_begin, element_end) of the
// global numbering): its MeshView holds those rows only, with global node ids in
// the connectivity, so no rank needs the whole mesh. The history is given whole on
// every rank and written by the root rank. Default: one process, every row.
struct Distribution {
  mpi::Communicator comm;
  std::size_t nodes = 0, elements = 0;  // of the whole mesh
  std::size_t node_begin = 0, node_end = 0, element_begin = 0, element_end = 0;
};

// The fields of one step. A null pointer is written as zeros when the field is
// requested in the deck (e.g. contact_force in a run without contact). On many
// ranks: this rank's rows only (Distribution).
struct StepData {
  long step = 0;
  double time = 0.0;
  const NodalVectors* displacement = nullptr;
  const NodalVectors* velocity = nullptr;
  const NodalVectors* acceleration = nullptr;
  const NodalVectors* contact_force = nullptr;
  const double* stress = nullptr;          // 6 E: xx yy zz xy yz xz per element
  const double* von_mises = nullptr;       // E
  const double* gap = nullptr;             // N
  const double* plastic_strain = nullptr;  // E: mean equivalent plastic strain (null: 0, elastic parts)
  const double* damage = nullptr;          // E: damage D (null: 0)
  const double* status = nullptr;          // E: 1 alive, 0 eroded (null: all 1)
  // Instead of the pointers (many ranks): writes this rank's rows of a requested field
  // straight into the step's buffer, in the file's layout ((rows, 3) or (rows, 6)
  // row-major, or (rows,)), so no rank keeps a copy of its rows beside the buffer.
  // Called on the caller's thread, once per requested field in the writer's order.
  std::function<void(input::OutputField field, double* rows)> fill_rows;
};

struct HistoryRow {
  double time = 0.0;
  double kinetic_energy = 0.0;
  double internal_energy = 0.0;
  double contact_energy = 0.0;
  double hourglass_energy = 0.0;
  double external_work = 0.0;
  double total_energy = 0.0;
  double plastic_work = 0.0;   // a part of internal_energy (docs/output.md)
  double friction_work = 0.0;  // a part of contact_energy (docs/output.md)
  double eroded_energy = 0.0;  // energy that left with eroded elements, in total_energy
  double eroded_mass = 0.0;    // mass that left with them, kg
};

// One history row of one contact pair.
struct ContactHistoryRow {
  std::array<double, 3> force{};  // total contact force on the pair's slave side, N
  double max_penetration = 0.0;   // the pair's deepest penetration at that step, m (>= 0)
  double normal_force = 0.0;      // |the normal part of force|, N
  double tangential_force = 0.0;  // |its tangential (friction) part|, N
  // The sums over the pair's points (both passes) of |F_n| and |F_t|, N: on a single
  // surface, whose force on itself cancels, what shows the contact.
  double normal_force_sum = 0.0;
  double tangential_force_sum = 0.0;
};

// One history row of one rigid wall.
struct WallHistoryRow {
  std::array<double, 3> force{};  // total force of the wall on the bodies, N
};

// The names of the groups under /history: contact pairs (/history/contact/NAME),
// rigid walls (/history/wall/NAME) and boundary conditions (/history/boundary/INDEX,
// their count).
struct HistoryGroups {
  std::vector<std::string> contact_pairs;
  std::vector<std::string> walls;
  std::size_t boundaries = 0;
  HistoryGroups() = default;
  HistoryGroups(std::vector<std::string> pairs, std::vector<std::string> wall_names = {})  // NOLINT: implicit
      : contact_pairs(std::move(pairs)), walls(std::move(wall_names)) {}
};

// Where a run stands in its files, as a checkpoint keeps it (docs/output.md,
// "Checkpoints"): the steps written and their times, the history rows on disk, and
// the output fields of each stretch of steps (a restart may change them: from_step).
struct FieldSet {
  long from_step = 0;
  std::vector<input::OutputField> fields;
};
struct WrittenPosition {
  std::vector<long> steps;
  std::vector<double> times;
  std::uint64_t history_rows = 0;
  std::vector<FieldSet> field_sets;
};

// Call from one thread (the serial HDF5 library is not thread-safe; the writer's
// own thread, in the background, is inside it only while the caller is not). HDF5 and
// file-system failures throw std::runtime_error naming the file and dataset;
// a caller's mistake (time not increasing, a field of the wrong size) throws
// std::logic_error before the file is touched; a bad mesh or name throws
// std::invalid_argument from the constructor.
class ResultWriter {
 public:
  // Creates (or overwrites) DIRECTORY/NAME.h5 with /mesh; creates DIRECTORY if
  // needed. NAME.xmf is written from the first step on (ParaView's Xdmf2 reader
  // crashes on a collection with no step); a NAME.xmf of an earlier run is removed.
  // groups: the names of the contact pairs, whose histories go to
  // /history/contact/NAME (one ContactHistoryRow each with every history row), and of
  // the rigid walls, /history/wall/NAME (one WallHistoryRow each).
  // expected_steps: how many steps the run plans to write; /steps is sized for
  // them, so that adding a step changes the file's structure in one place
  // (hdf5_support.hpp, create_step_group). More steps are fine.
  // resume: instead, go on writing the NAME.h5 and NAME.xmf of a run that stood at
  // *resume (a restart): the steps after it and the history rows beyond it are
  // removed, and this writer's fields are those of the steps from resume_step on.
  ResultWriter(const std::string& directory, const std::string& name, const MeshView& mesh,
               const std::vector<input::OutputField>& fields, const HistoryGroups& groups = {},
               std::size_t expected_steps = 64, const Distribution& distribution = {},
               const WrittenPosition* resume = nullptr, long resume_step = 0);
  ~ResultWriter();
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  // Buffers a history row, with one row per contact pair and one per rigid wall then
  // per boundary condition (the reaction force: WallHistoryRow), in the constructor's
  // order; rows are flushed to /history at every write_step and flush().
  void add_history(const HistoryRow& row, const std::vector<ContactHistoryRow>& contact = {},
                   const std::vector<WallHistoryRow>& walls = {});
  // Writes /steps/NNNNNN, appends to /time, flushes history, closes the file,
  // then rewrites the .xmf atomically. Steps must come in strictly increasing
  // time and step number. In the background (write_in_background), the step is
  // copied and the call returns; the writer's thread writes it while the caller goes
  // on, and the next call waits for it (and throws its error, if it had one).
  void write_step(const StepData& data);
  // Steps are written by a thread of the writer's own, one at a time, instead of by
  // the caller (on one rank only: on many, MPI is called from the main thread).
  // Call before the first write_step. The files on disk go through the
  // same states in the same order: a kill leaves what it leaves without the thread.
  void write_in_background(bool background);
  // Waits for a step in flight, then flushes buffered history rows (end of run).
  void flush();
  // What is on disk after flush(): the position a checkpoint keeps.
  WrittenPosition position();

  std::string h5_path() const;
  std::string xmf_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace exdyn::output
