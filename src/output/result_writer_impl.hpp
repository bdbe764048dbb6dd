// The inside of the result writer (result_writer.hpp), shared by its files:
// result_writer.cpp (steps, the .xmf, the writer thread) and result_writer_layout.cpp
// (the mesh and the history datasets). Not for use outside src/output.
#pragma once

#include <hdf5.h>

#include <array>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "output/hdf5_support.hpp"
#include "output/result_writer.hpp"
#include "output/xdmf_text.hpp"

namespace exdyn::output {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// Fields: dataset name, where it lives, and how XDMF describes it.

enum class Center { node, cell };

struct FieldLayout {
  input::OutputField field;
  const char* dataset;  // name in /steps/NNNNNN and in ParaView
  Center center;
  int components;              // 1 = stored as (n,), otherwise (n, components)
  const char* attribute_type;  // XDMF AttributeType
};

// Canonical order: datasets and XDMF attributes appear in this order whatever
// the order of the deck's list, so that files of different runs compare.
// Stress is "Matrix" E x 6: every ParaView 5.11 XDMF reader keeps 6 components
// labelled XX YY ZZ XY YZ XZ ("Tensor6" is expanded to 9 by the Xdmf2 reader).
inline constexpr std::array<FieldLayout, 10> field_layouts{{
    {input::OutputField::displacement, "displacement", Center::node, 3, "Vector"},
    {input::OutputField::velocity, "velocity", Center::node, 3, "Vector"},
    {input::OutputField::acceleration, "acceleration", Center::node, 3, "Vector"},
    {input::OutputField::stress, "stress", Center::cell, 6, "Matrix"},
    {input::OutputField::von_mises, "von_mises", Center::cell, 1, "Scalar"},
    {input::OutputField::contact_force, "contact_force", Center::node, 3, "Vector"},
    {input::OutputField::gap, "gap", Center::node, 1, "Scalar"},
    {input::OutputField::plastic_strain, "plastic_strain", Center::cell, 1, "Scalar"},
    {input::OutputField::damage, "damage", Center::cell, 1, "Scalar"},
    {input::OutputField::status, "status", Center::cell, 1, "Scalar"},
}};

using HistoryColumn = std::pair<const char*, double HistoryRow::*>;
inline constexpr std::array<HistoryColumn, 11> history_columns{{
    {"time", &HistoryRow::time},
    {"kinetic_energy", &HistoryRow::kinetic_energy},
    {"internal_energy", &HistoryRow::internal_energy},
    {"contact_energy", &HistoryRow::contact_energy},
    {"hourglass_energy", &HistoryRow::hourglass_energy},
    {"external_work", &HistoryRow::external_work},
    {"total_energy", &HistoryRow::total_energy},
    {"plastic_work", &HistoryRow::plastic_work},
    {"friction_work", &HistoryRow::friction_work},
    {"eroded_energy", &HistoryRow::eroded_energy},
    {"eroded_mass", &HistoryRow::eroded_mass},
}};

inline std::string step_group_name(long step) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%06ld", step);
  return text.data();
}

// ---------------------------------------------------------------------------

// One step, ready for the file: each requested field as the rows it is stored in,
// and the history rows buffered since the last step.
struct Frame {
  long step = 0;
  double time = 0.0;
  std::vector<std::vector<double>> values;  // per requested field (Impl::fields), reused
  std::vector<HistoryRow> history;
  std::vector<ContactHistoryRow> contact;  // contact_pairs.size() per history row
  std::vector<WallHistoryRow> walls;       // walls.size() per history row
};

struct ResultWriter::Impl {
  fs::path h5_file;
  fs::path xmf_file;
  std::string h5_reference;  // "NAME.h5", relative to the .xmf's directory, XML-escaped
  hdf5::Hdf5Errors errors;
  std::size_t node_count = 0;
  std::size_t element_count = 0;
  unsigned expected_steps = 0;             // the /steps group is sized for this many links
  std::vector<const FieldLayout*> fields;  // requested, canonical order, no duplicates

  std::vector<double> buffer;  // interleaved (AoS) staging and zeros; reused
  std::vector<HistoryRow> pending_history;
  std::vector<std::string> contact_pairs;          // names, for /history/contact/NAME
  std::vector<ContactHistoryRow> pending_contact;  // contact_pairs.size() per pending history row
  // The groups of a force series: /history/wall/NAME, then /history/boundary/INDEX.
  std::vector<std::string> walls;
  std::vector<WallHistoryRow> pending_walls;  // walls.size() per pending history row
  hsize_t history_rows_on_disk = 0;
  // Elements of 8 and 20 nodes mixed: the .xmf names /mesh/mixed_topology (XDMF "Mixed").
  bool mixed = false;
  int nodes_per_element = 8;  // 8 or 20 when not mixed
  std::size_t mixed_topology_size = 0;
  hsize_t steps_on_disk = 0;
  std::optional<double> last_time;
  long last_step = -1;
  std::vector<std::string> step_xml;  // one <Grid> per written step
  std::vector<long> written_steps;    // and its step and time
  std::vector<double> written_times;
  std::vector<FieldSet> field_sets;  // the fields of each stretch of steps; the last: `fields`
  Frame frame;                       // the step being written, or the last one

  // The writer thread (write_in_background): it writes `frame` when `busy` is set and
  // clears `busy` when done; the caller fills `frame` only while `busy` is clear.
  bool background = false;
  std::thread thread;
  std::mutex mutex;
  std::condition_variable wake, written;
  bool busy = false, stopping = false;
  std::exception_ptr failure;  // the writer thread's error, thrown by the caller's next call

  Distribution distribution;  // comm.size > 1: this rank's rows of the step fields

  Impl(const fs::path& directory, const std::string& name, const Distribution& d)
      : h5_file(directory / (name + ".h5")),
        xmf_file(directory / (name + ".xmf")),
        h5_reference(xdmf::escape(name + ".h5")),
        errors(h5_file.string(), d.comm.distributed() ? d.comm.comm : MPI_COMM_NULL, d.comm.root()),
        distribution(d) {}

  void write_mesh(const MeshView& mesh);
  void write_history(hid_t file, const std::vector<HistoryRow>& rows,
                     const std::vector<ContactHistoryRow>& contact_rows,
                     const std::vector<WallHistoryRow>& wall_rows);
  void fill_frame(const StepData& data);
  void fill_field(std::vector<double>& out, const FieldLayout& layout, const StepData& data);
  void write_frame();
  void wait_until_written();
  void writer_loop();
  std::string grid_xml(double time, const std::string& group,
                       const std::vector<const FieldLayout*>& step_fields) const;
  void resume(const WrittenPosition& position, long resume_step);
  std::vector<const FieldLayout*> layouts_of(const std::vector<input::OutputField>& requested) const;
  void write_xdmf() const;
  void remove_stale_xdmf() const;

  std::size_t rows(Center center) const { return center == Center::node ? node_count : element_count; }
  // The rows of the step fields this process holds and writes: [first_row, + held_rows).
  std::size_t first_row(Center center) const {
    if (!distribution.comm.distributed()) return 0;
    return center == Center::node ? distribution.node_begin : distribution.element_begin;
  }
  std::size_t held_rows(Center center) const {
    if (!distribution.comm.distributed()) return rows(center);
    return center == Center::node ? distribution.node_end - distribution.node_begin
                                  : distribution.element_end - distribution.element_begin;
  }
};

}  // namespace exdyn::output
