// HDF5 + XDMF result writer (../shared/spec/output.md,
// ../shared/tools/paraview/README.md "Recommended layout").
//
// Every public operation opens NAME.h5, writes whole datasets from one buffer,
// and closes the file again: HDF5 1.10 locks an open file, and ParaView aborts
// on a locked file, so the file is only held while we write. The .xmf is
// rewritten (temporary + rename) only after the HDF5 file is closed, so it
// never names a step that is not complete on disk.
//
// A step is first copied into a Frame (the rows the file stores, and the history
// rows since the last step); the Frame is then written, by the caller or, in the
// background, by the writer's own thread while the caller goes on computing. Only
// one thread is inside HDF5 at any time (the serial library is not thread-safe):
// the caller waits for the writer thread before every operation that touches the
// file.
#include "output/result_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>

#include "common/parallel.hpp"
#include "output/atomic_file.hpp"
#include "output/hdf5_support.hpp"
#include "output/result_writer_impl.hpp"
#include "output/xdmf_text.hpp"

namespace exdyn::output {

using namespace hdf5;

// The rows of one field as the file stores them: (N, 3) or (E, 6) row-major, or
// (N,) / (E,); zeros (status: ones) for a requested field the solver did not provide.
void ResultWriter::Impl::fill_field(std::vector<double>& out, const FieldLayout& layout,
                                    const StepData& data) {
  const std::size_t n = held_rows(layout.center);
  const std::size_t count = n * static_cast<std::size_t>(layout.components);
  const double* values = nullptr;
  const NodalVectors* vectors = nullptr;
  switch (layout.field) {
    case input::OutputField::displacement:
      vectors = data.displacement;
      break;
    case input::OutputField::velocity:
      vectors = data.velocity;
      break;
    case input::OutputField::acceleration:
      vectors = data.acceleration;
      break;
    case input::OutputField::contact_force:
      vectors = data.contact_force;
      break;
    case input::OutputField::stress:
      values = data.stress;
      break;
    case input::OutputField::von_mises:
      values = data.von_mises;
      break;
    case input::OutputField::gap:
      values = data.gap;
      break;
    case input::OutputField::plastic_strain:
      values = data.plastic_strain;
      break;
    case input::OutputField::damage:
      values = data.damage;
      break;
    case input::OutputField::status:
      values = data.status;
      break;
  }
  out.resize(count);
  if (data.fill_rows) {
    data.fill_rows(layout.field, out.data());
    return;
  }
  if (vectors == nullptr && values == nullptr) {  // status: every element alive
    std::fill(out.begin(), out.end(), layout.field == input::OutputField::status ? 1.0 : 0.0);
    return;
  }
  // On the threads in blocks of 16,384 rows (the write itself is serial).
  const std::size_t block = 16384, components = static_cast<std::size_t>(layout.components);
  parallel_for_static(static_cast<std::ptrdiff_t>(chunk_count(n, block)), [&](std::ptrdiff_t k) {
    const std::size_t begin = static_cast<std::size_t>(k) * block, end = std::min(n, begin + block);
    if (vectors != nullptr) {  // SoA to (N, 3) rows
      for (std::size_t i = begin; i < end; ++i) {
        out[3 * i] = vectors->x[i];
        out[3 * i + 1] = vectors->y[i];
        out[3 * i + 2] = vectors->z[i];
      }
    } else {  // stress: ParaView's order xx yy zz xy yz xz, as it comes
      std::copy(values + components * begin, values + components * end,
                out.begin() + std::ptrdiff_t(components * begin));
    }
  });
}

// Copies a step into `frame` (the caller's thread; the writer thread is idle).
void ResultWriter::Impl::fill_frame(const StepData& data) {
  frame.step = data.step;
  frame.time = data.time;
  frame.values.resize(fields.size());
  for (std::size_t k = 0; k < fields.size(); ++k) fill_field(frame.values[k], *fields[k], data);
  frame.history.swap(pending_history);
  frame.contact.swap(pending_contact);
  frame.walls.swap(pending_walls);
  pending_history.clear();
  pending_contact.clear();
  pending_walls.clear();
}

// Writes `frame` to NAME.h5, closes it, then names the step in the .xmf.
void ResultWriter::Impl::write_frame() {
  const Hdf5ErrorPrintingOff quiet;
  const std::string group_name = step_group_name(frame.step);
  const std::string group_path = "/steps/" + group_name;
  {
    Hdf5File file(errors, Hdf5File::Mode::append);
    {
      Handle group = create_group(errors, file.get(), group_path);
      write_scalar_attribute(errors, group.get(), group_path, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                             &frame.time);
      const std::int64_t step = frame.step;
      write_scalar_attribute(errors, group.get(), group_path, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, &step);
    }
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const FieldLayout& layout = *fields[k];
      std::vector<hsize_t> dims{rows(layout.center)};
      if (layout.components > 1) dims.push_back(static_cast<hsize_t>(layout.components));
      write_dataset(errors, file.get(), group_path + "/" + layout.dataset, dims, H5T_IEEE_F64LE,
                    H5T_NATIVE_DOUBLE, frame.values[k].data(),
                    std::pair<hsize_t, hsize_t>{first_row(layout.center), held_rows(layout.center)});
    }
    append_series(errors, file.get(), "/time", steps_on_disk, {frame.time});
    write_history(file.get(), frame.history, frame.contact, frame.walls);
    file.close();
  }
  // Only now is the step on disk: record it, then let readers see it.
  steps_on_disk += 1;
  history_rows_on_disk += frame.history.size();
  step_xml.push_back(grid_xml(frame.time, group_name, fields));
  written_steps.push_back(frame.step);
  written_times.push_back(frame.time);
  write_xdmf();
}

// Waits until the writer thread has no frame; throws its error, if it had one.
void ResultWriter::Impl::wait_until_written() {
  if (!background) return;
  std::unique_lock lock(mutex);
  written.wait(lock, [&] { return !busy; });
  if (failure) std::rethrow_exception(std::exchange(failure, nullptr));
}

void ResultWriter::Impl::writer_loop() {
  std::unique_lock lock(mutex);
  for (;;) {
    wake.wait(lock, [&] { return busy || stopping; });
    if (!busy) return;  // stopping, nothing left to write
    lock.unlock();
    std::exception_ptr error;
    try {
      write_frame();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    failure = error;
    busy = false;
    written.notify_all();
  }
}

std::string ResultWriter::Impl::grid_xml(double time, const std::string& group,
                                         const std::vector<const FieldLayout*>& step_fields) const {
  xdmf::Grid grid{h5_reference, node_count, element_count, mixed, mixed_topology_size, nodes_per_element, {}};
  for (const FieldLayout* layout : step_fields)
    grid.attributes.push_back(
        {layout->dataset, layout->center == Center::node, layout->components, layout->attribute_type});
  return xdmf::grid(grid, time, group);
}

void ResultWriter::Impl::write_xdmf() const {
  if (!errors.root()) return;  // on many ranks the root writes the .xmf
  std::vector<std::string_view> parts;
  parts.reserve(step_xml.size() + 2);
  parts.push_back(xdmf::head);
  for (const std::string& grid : step_xml) parts.push_back(grid);
  parts.push_back(xdmf::tail);
  write_file_atomically(xmf_file, parts);
}

void ResultWriter::Impl::remove_stale_xdmf() const {
  if (!errors.root()) return;
  for (fs::path stale : {xmf_file, fs::path(xmf_file.string() + ".tmp")}) {
    std::error_code error;
    fs::remove(stale, error);
    if (error)
      throw std::runtime_error("cannot remove " + stale.string() + " of an earlier run: " + error.message());
  }
}

// ---------------------------------------------------------------------------

ResultWriter::ResultWriter(const std::string& directory, const std::string& name, const MeshView& mesh,
                           const std::vector<input::OutputField>& fields, const HistoryGroups& groups,
                           std::size_t expected_steps, const Distribution& distribution,
                           const WrittenPosition* resume, long resume_step) {
  // Names end up in "NAME.h5:/path" inside the .xmf, which the XDMF readers
  // split at the colon; a slash would put the files somewhere else.
  if (name.empty() || name.find_first_of(":/\\") != std::string::npos) {
    throw std::invalid_argument("result name '" + name +
                                "' must be non-empty and contain no ':', '/' or '\\'");
  }
  if (mesh.x_ref == nullptr || mesh.connectivity == nullptr) {
    throw std::invalid_argument("ResultWriter: mesh coordinates and connectivity are required");
  }
  // On many ranks the mesh is this rank's rows, of a mesh of distribution.nodes nodes
  // and distribution.elements elements.
  const bool rows_given = distribution.comm.distributed();
  const std::size_t held_nodes = mesh.x_ref->size();
  if (mesh.x_ref->y.size() != held_nodes || mesh.x_ref->z.size() != held_nodes) {
    throw std::invalid_argument("ResultWriter: coordinate components differ in length");
  }
  if (rows_given && held_nodes != distribution.node_end - distribution.node_begin)
    throw std::invalid_argument("ResultWriter: " + std::to_string(held_nodes) + " coordinate rows for rows " +
                                std::to_string(distribution.node_begin) + " to " +
                                std::to_string(distribution.node_end));
  const std::size_t node_count = rows_given ? distribution.nodes : held_nodes;
  // Elements of 8 nodes, or of the sizes element_nodes gives (8 or 20).
  std::size_t element_count = mesh.connectivity->size() / 8;
  bool has_8 = true, has_20 = false;
  if (mesh.element_nodes != nullptr) {
    element_count = mesh.element_nodes->size();
    std::size_t total = 0;
    has_8 = false;
    for (const std::uint8_t nodes : *mesh.element_nodes) {
      if (nodes != 8 && nodes != 20)
        throw std::invalid_argument("ResultWriter: an element of " + std::to_string(nodes) +
                                    " nodes (8 or 20 expected)");
      (nodes == 8 ? has_8 : has_20) = true;
      total += nodes;
    }
    if (total != mesh.connectivity->size())
      throw std::invalid_argument("ResultWriter: connectivity length " +
                                  std::to_string(mesh.connectivity->size()) + " is not the " +
                                  std::to_string(total) + " nodes of the elements");
  } else if (mesh.connectivity->size() % 8 != 0) {
    throw std::invalid_argument("ResultWriter: connectivity length " +
                                std::to_string(mesh.connectivity->size()) + " is not a multiple of 8");
  }
  if (rows_given) {
    if (element_count != distribution.element_end - distribution.element_begin)
      throw std::invalid_argument("ResultWriter: " + std::to_string(element_count) +
                                  " element rows for rows " + std::to_string(distribution.element_begin) +
                                  " to " + std::to_string(distribution.element_end));
    // Whether the whole mesh mixes 8- and 20-node elements.
    int sizes[2] = {has_8 ? 1 : 0, has_20 ? 1 : 0};
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, sizes, 2, MPI_INT, MPI_MAX, distribution.comm.comm),
               "MPI_Allreduce of the element sizes");
    has_8 = sizes[0] != 0;
    has_20 = sizes[1] != 0;
  }
  if (mesh.element_part != nullptr && mesh.element_part->size() != element_count) {
    throw std::invalid_argument("ResultWriter: " + std::to_string(mesh.element_part->size()) +
                                " part indices for " + std::to_string(element_count) + " elements");
  }
  // ParaView reads an out-of-range node index without complaint and draws garbage.
  for (std::size_t i = 0; i < mesh.connectivity->size(); ++i) {
    if ((*mesh.connectivity)[i] >= node_count) {
      throw std::invalid_argument("ResultWriter: connectivity entry " + std::to_string(i) + " names node " +
                                  std::to_string((*mesh.connectivity)[i]) + " of " +
                                  std::to_string(node_count));
    }
  }
  for (const auto* names : {&groups.contact_pairs, &groups.walls})
    for (const std::string& name_of_group : *names)
      if (name_of_group.empty() || name_of_group.find('/') != std::string::npos || name_of_group == "." ||
          name_of_group == "..")
        throw std::invalid_argument(std::string("ResultWriter: ") +
                                    (names == &groups.walls ? "rigid wall" : "contact pair") + " name '" +
                                    name_of_group + "' cannot name an HDF5 group");

  fs::create_directories(directory);
  impl_ = std::make_unique<Impl>(fs::path(directory), name, distribution);
  impl_->node_count = node_count;
  impl_->element_count = rows_given ? distribution.elements : element_count;
  impl_->expected_steps = static_cast<unsigned>(std::min<std::size_t>(expected_steps, 65535));
  impl_->mixed = has_8 && has_20;
  impl_->nodes_per_element = has_20 ? 20 : 8;
  impl_->contact_pairs = groups.contact_pairs;
  for (const std::string& wall : groups.walls) impl_->walls.push_back("/history/wall/" + wall);
  for (std::size_t b = 0; b < groups.boundaries; ++b)
    impl_->walls.push_back("/history/boundary/" + std::to_string(b));
  impl_->fields = impl_->layouts_of(fields);
  // The step fields' buffers, allocated and touched here, at setup: their first zero
  // fill (page faults, serial) was 1-3 % of a 110,592-brick run's time loop.
  impl_->frame.values.resize(impl_->fields.size());
  for (std::size_t k = 0; k < impl_->fields.size(); ++k)
    impl_->frame.values[k].resize(impl_->held_rows(impl_->fields[k]->center) *
                                  static_cast<std::size_t>(impl_->fields[k]->components));

  // The .xmf appears with the first step, not here: a temporal collection
  // with no grid crashes ParaView 5.11's "XDMF Reader" (Xdmf2: "Grid has 0
  // children", SIGSEGV; the two Xdmf3 readers show an empty dataset). A .xmf
  // left by an earlier run goes first, before the .h5 it names is truncated
  // (ParaView aborts on a missing dataset).
  const Hdf5ErrorPrintingOff quiet;
  if (resume != nullptr) {
    impl_->resume(*resume, resume_step);
    return;
  }
  impl_->field_sets.push_back({0, fields});
  impl_->remove_stale_xdmf();
  impl_->write_mesh(mesh);
}

std::vector<const FieldLayout*> ResultWriter::Impl::layouts_of(
    const std::vector<input::OutputField>& requested) const {
  std::vector<const FieldLayout*> out;
  for (const FieldLayout& layout : field_layouts)
    if (std::find(requested.begin(), requested.end(), layout.field) != requested.end())
      out.push_back(&layout);
  return out;
}

ResultWriter::~ResultWriter() {
  // Last chance for a frame in flight and history rows of a run that ended without
  // flush() (an exception unwinding the solver). A destructor cannot throw, and the
  // run is already ending, so a failure here is dropped; flush() is the checked path.
  if (impl_ == nullptr) return;
  try {
    impl_->wait_until_written();
  } catch (...) {
  }
  if (impl_->thread.joinable()) {
    {
      const std::lock_guard lock(impl_->mutex);
      impl_->stopping = true;
    }
    impl_->wake.notify_all();
    impl_->thread.join();
  }
  impl_->background = false;
  if (impl_->pending_history.empty()) return;
  try {
    flush();
  } catch (...) {
  }
}

void ResultWriter::write_in_background(bool background) {
  Impl& w = *impl_;
  if (w.thread.joinable() || w.written_steps.size() != w.steps_on_disk)
    throw std::logic_error("ResultWriter::write_in_background: a step is already written");
  w.background = background && !w.distribution.comm.distributed();
}

void ResultWriter::add_history(const HistoryRow& row, const std::vector<ContactHistoryRow>& contact,
                               const std::vector<WallHistoryRow>& walls) {
  if (contact.size() != impl_->contact_pairs.size())
    throw std::logic_error("ResultWriter::add_history: " + std::to_string(contact.size()) +
                           " contact rows for " + std::to_string(impl_->contact_pairs.size()) + " pairs");
  if (walls.size() != impl_->walls.size())
    throw std::logic_error("ResultWriter::add_history: " + std::to_string(walls.size()) +
                           " wall and boundary rows for " + std::to_string(impl_->walls.size()));
  impl_->pending_walls.insert(impl_->pending_walls.end(), walls.begin(), walls.end());
  impl_->pending_history.push_back(row);
  impl_->pending_contact.insert(impl_->pending_contact.end(), contact.begin(), contact.end());
}

void ResultWriter::write_step(const StepData& data) {
  Impl& w = *impl_;
  if (!std::isfinite(data.time)) {
    throw std::logic_error("ResultWriter: step " + std::to_string(data.step) + " has a non-finite time");
  }
  if (w.last_time && !(data.time > *w.last_time)) {
    throw std::logic_error("ResultWriter: step " + std::to_string(data.step) + " at time " +
                           xdmf::format_time(data.time) + " does not come after the last written time " +
                           xdmf::format_time(*w.last_time));
  }
  if (data.step < 0 || data.step <= w.last_step) {
    throw std::logic_error("ResultWriter: step number " + std::to_string(data.step) +
                           " does not come after the last written step " + std::to_string(w.last_step));
  }

  // Sizes are checked before the file is touched, so a caller's mistake leaves no partial step.
  const std::size_t held_nodes = w.held_rows(Center::node);
  auto check_nodes = [&](const NodalVectors* vectors, const char* what) {
    if (vectors == nullptr) return;
    if (vectors->x.size() != held_nodes || vectors->y.size() != held_nodes ||
        vectors->z.size() != held_nodes) {
      throw std::logic_error("ResultWriter: step " + std::to_string(data.step) + ": " + what + " has " +
                             std::to_string(vectors->size()) + " nodes, the mesh " +
                             std::to_string(held_nodes));
    }
  };
  check_nodes(data.displacement, "displacement");
  check_nodes(data.velocity, "velocity");
  check_nodes(data.acceleration, "acceleration");
  check_nodes(data.contact_force, "contact_force");

  // The writer thread has finished the last frame (its error, if any, is thrown here):
  // this step's frame may be filled.
  w.wait_until_written();
  w.fill_frame(data);
  w.last_time = data.time;
  w.last_step = data.step;
  if (!w.background) {
    w.write_frame();
    return;
  }
  if (!w.thread.joinable()) w.thread = std::thread([&w] { w.writer_loop(); });
  {
    const std::lock_guard lock(w.mutex);
    w.busy = true;
  }
  w.wake.notify_one();
}

void ResultWriter::flush() {
  Impl& w = *impl_;
  w.wait_until_written();
  if (w.pending_history.empty()) return;
  const Hdf5ErrorPrintingOff quiet;
  Hdf5File file(w.errors, Hdf5File::Mode::append);
  w.write_history(file.get(), w.pending_history, w.pending_contact, w.pending_walls);
  file.close();
  w.history_rows_on_disk += w.pending_history.size();
  w.pending_history.clear();
  w.pending_contact.clear();
  w.pending_walls.clear();
}

WrittenPosition ResultWriter::position() {
  flush();
  return {impl_->written_steps, impl_->written_times, impl_->history_rows_on_disk, impl_->field_sets};
}

std::string ResultWriter::h5_path() const { return impl_->h5_file.string(); }
std::string ResultWriter::xmf_path() const { return impl_->xmf_file.string(); }

}  // namespace exdyn::output
