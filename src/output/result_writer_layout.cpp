// The mesh and history datasets of NAME.h5 (../shared/spec/output.md): the layout
// the result writer (result_writer_impl.hpp) creates once and appends rows to.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "output/result_writer_impl.hpp"

namespace exdyn::output {

using namespace hdf5;

void ResultWriter::Impl::write_mesh(const MeshView& mesh) {
  Hdf5File file(errors, Hdf5File::Mode::create);
  create_group(errors, file.get(), "/mesh");
  create_step_group(errors, file.get(), "/steps", expected_steps);
  create_group(errors, file.get(), "/history");

  // Coordinates: SoA in memory, (N, 3) row-major on disk. On many ranks each writes
  // the rows it holds (Distribution), of the mesh as of the step fields.
  const NodalVectors& x = *mesh.x_ref;
  const std::size_t held_nodes = held_rows(Center::node), held_elements = held_rows(Center::cell);
  buffer.resize(std::max(buffer.size(), 3 * held_nodes));
  for (std::size_t i = 0; i < held_nodes; ++i) {
    buffer[3 * i] = x.x[i];
    buffer[3 * i + 1] = x.y[i];
    buffer[3 * i + 2] = x.z[i];
  }
  write_dataset(errors, file.get(), "/mesh/coordinates", {node_count, 3}, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                buffer.data(), std::pair<hsize_t, hsize_t>{first_row(Center::node), held_nodes});

  // Connectivity: uint32 in memory; int64 on disk, the type every XDMF reader
  // and numpy index with (a uint32 DataItem would need NumberType="UInt").
  // (E, 8) or (E, 20) when every element has that many nodes. A mesh with both
  // writes (E, 20) with the rows of 8-node elements padded with -1, and for ParaView
  // /mesh/mixed_topology, XDMF's "Mixed" list: per element its cell type (9
  // Hexahedron, 48 Hexahedron_20) then its nodes (docs/output.md).
  const std::pair<hsize_t, hsize_t> element_rows{first_row(Center::cell), held_elements};
  {
    const std::vector<std::uint32_t>& connectivity = *mesh.connectivity;
    const std::size_t width = mixed ? 20 : static_cast<std::size_t>(nodes_per_element);
    std::vector<std::int64_t> connectivity64(held_elements * width, -1);
    std::vector<std::int64_t> mixed_topology;
    std::size_t next = 0;
    for (std::size_t e = 0; e < held_elements; ++e) {
      const std::size_t nodes = mesh.element_nodes == nullptr ? 8 : (*mesh.element_nodes)[e];
      if (mixed) mixed_topology.push_back(nodes == 20 ? 48 : 9);
      for (std::size_t k = 0; k < nodes; ++k) {
        connectivity64[width * e + k] = connectivity[next + k];
        if (mixed) mixed_topology.push_back(connectivity[next + k]);
      }
      next += nodes;
    }
    write_dataset(errors, file.get(), "/mesh/connectivity", {element_count, width}, H5T_STD_I64LE,
                  H5T_NATIVE_INT64, connectivity64.data(), element_rows);
    if (mixed) {
      // On many ranks the list's pieces one after the other in rank (= element) order.
      auto held = static_cast<unsigned long long>(mixed_topology.size());
      unsigned long long offset = 0, total = held;
      if (distribution.comm.distributed()) {
        mpi::check(MPI_Exscan(&held, &offset, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, distribution.comm.comm),
                   "MPI_Exscan of the mixed topology");
        if (distribution.comm.root()) offset = 0;  // MPI_Exscan leaves rank 0's undefined
        mpi::check(MPI_Allreduce(&held, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, distribution.comm.comm),
                   "MPI_Allreduce of the mixed topology");
      }
      mixed_topology_size = std::size_t(total);
      write_dataset(errors, file.get(), "/mesh/mixed_topology", {hsize_t(total)}, H5T_STD_I64LE,
                    H5T_NATIVE_INT64, mixed_topology.data(), std::pair<hsize_t, hsize_t>{offset, held});
    }
  }

  // Part index per element; a mesh without parts is one part, index 0.
  if (mesh.element_part != nullptr) {
    write_dataset(errors, file.get(), "/mesh/part", {element_count}, H5T_STD_I32LE, H5T_NATIVE_INT32,
                  mesh.element_part->data(), element_rows);
  } else {
    const std::vector<std::int32_t> single_part(held_elements, 0);
    write_dataset(errors, file.get(), "/mesh/part", {element_count}, H5T_STD_I32LE, H5T_NATIVE_INT32,
                  single_part.data(), element_rows);
  }

  create_series(errors, file.get(), "/time");
  for (const auto& [column, member] : history_columns) {
    create_series(errors, file.get(), std::string("/history/") + column);
  }
  if (!contact_pairs.empty()) {
    create_group(errors, file.get(), "/history/contact");
    for (const std::string& pair : contact_pairs) {
      create_group(errors, file.get(), "/history/contact/" + pair);
      create_series(errors, file.get(), "/history/contact/" + pair + "/force", 3);
      create_series(errors, file.get(), "/history/contact/" + pair + "/max_penetration");
      create_series(errors, file.get(), "/history/contact/" + pair + "/normal_force");
      create_series(errors, file.get(), "/history/contact/" + pair + "/tangential_force");
      create_series(errors, file.get(), "/history/contact/" + pair + "/normal_force_sum");
      create_series(errors, file.get(), "/history/contact/" + pair + "/tangential_force_sum");
    }
  }
  for (const char* parent : {"/history/wall/", "/history/boundary/"}) {
    bool first = true;
    for (const std::string& group : walls) {
      if (group.rfind(parent, 0) != 0) continue;
      if (first) create_group(errors, file.get(), std::string(parent, std::strlen(parent) - 1));
      first = false;
      create_group(errors, file.get(), group);
      create_series(errors, file.get(), group + "/force", 3);
    }
  }
  file.close();
}

void ResultWriter::Impl::write_history(hid_t file, const std::vector<HistoryRow>& rows,
                                       const std::vector<ContactHistoryRow>& contact_rows,
                                       const std::vector<WallHistoryRow>& wall_rows) {
  if (rows.empty()) return;
  std::vector<double> column_values(rows.size());
  for (const auto& [column, member] : history_columns) {
    for (std::size_t i = 0; i < rows.size(); ++i) column_values[i] = rows[i].*member;
    append_series(errors, file, std::string("/history/") + column, history_rows_on_disk, column_values);
  }
  const std::size_t pairs = contact_pairs.size();
  std::vector<double> force(3 * rows.size());
  for (std::size_t k = 0; k < pairs; ++k) {
    const std::string group = "/history/contact/" + contact_pairs[k];
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (int c = 0; c < 3; ++c)
        force[3 * i + std::size_t(c)] = contact_rows[pairs * i + k].force[std::size_t(c)];
    append_series(errors, file, group + "/force", history_rows_on_disk, force, 3);
    for (const auto& [column, member] :
         {std::pair{"/max_penetration", &ContactHistoryRow::max_penetration},
          std::pair{"/normal_force", &ContactHistoryRow::normal_force},
          std::pair{"/tangential_force", &ContactHistoryRow::tangential_force},
          std::pair{"/normal_force_sum", &ContactHistoryRow::normal_force_sum},
          std::pair{"/tangential_force_sum", &ContactHistoryRow::tangential_force_sum}}) {
      for (std::size_t i = 0; i < rows.size(); ++i) column_values[i] = contact_rows[pairs * i + k].*member;
      append_series(errors, file, group + column, history_rows_on_disk, column_values);
    }
  }
  const std::size_t wall_count = walls.size();
  for (std::size_t k = 0; k < wall_count; ++k) {
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (int c = 0; c < 3; ++c)
        force[3 * i + std::size_t(c)] = wall_rows[wall_count * i + k].force[std::size_t(c)];
    append_series(errors, file, walls[k] + "/force", history_rows_on_disk, force, 3);
  }
}

}  // namespace exdyn::output
