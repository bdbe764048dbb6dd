// HDF5 plumbing of the result writer (private to src/output): RAII handles, error
// messages that name the file and the object, one file session, whole-dataset
// writes and the extendable series of /time and /history.
#pragma once

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace exdyn::output::hdf5 {

// Chunk of the extendable series (/time, /history/*): 1024 rows, so that
// appending a few rows at a time does not rewrite large chunks.
inline constexpr hsize_t series_chunk_rows = 1024;

// Owns one HDF5 identifier and closes it with the matching H5?close. The
// unchecked close in the destructor only runs on an error path; the file
// itself is closed with a checked call (Hdf5File::close).
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  hid_t release() { return std::exchange(id_, H5I_INVALID_HID); }
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// HDF5 prints its error stack to stderr by default. While we are inside the
// library we switch that off and put the stack into the exception message
// instead, then restore whatever handler the program had.
class Hdf5ErrorPrintingOff {
 public:
  Hdf5ErrorPrintingOff() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &client_data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~Hdf5ErrorPrintingOff() { H5Eset_auto2(H5E_DEFAULT, function_, client_data_); }
  Hdf5ErrorPrintingOff(const Hdf5ErrorPrintingOff&) = delete;
  Hdf5ErrorPrintingOff& operator=(const Hdf5ErrorPrintingOff&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* client_data_ = nullptr;
};

// The innermost messages of the current HDF5 error stack, e.g.
// "unable to lock file, errno = 11, error message = 'Resource temporarily unavailable'".
inline std::string hdf5_error_stack() {
  std::vector<std::string> messages;
  auto collect = [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
    auto& list = *static_cast<std::vector<std::string>*>(data);
    if (error->desc != nullptr && error->desc[0] != '\0') list.emplace_back(error->desc);
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect, &messages);
  H5Eclear2(H5E_DEFAULT);
  std::string text;
  // The deepest three say what went wrong; the outer ones repeat the call chain.
  const std::size_t first = messages.size() > 3 ? messages.size() - 3 : 0;
  for (std::size_t i = first; i < messages.size(); ++i) {
    if (!text.empty()) text += "; ";
    text += messages[i];
  }
  // Some HDF5 messages contain a ctime() date with its newline; keep the message on one line.
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text.empty() ? std::string("no HDF5 error detail") : text;
}

// Errors name the file and the object: "HDF5: cannot write dataset
// /steps/000010/stress in results/run.h5 (...)". It is also the file's context:
// on many ranks (comm set) the file is opened by all of them with the MPI-IO driver,
// every call below is collective, and the data is written collectively, each rank
// its own rows (the root rank alone those of a whole dataset or series).
class Hdf5Errors {
 public:
  explicit Hdf5Errors(std::string file, MPI_Comm comm = MPI_COMM_NULL, bool root = true)
      : file_(std::move(file)), comm_(comm), root_(root) {}
  MPI_Comm comm() const { return comm_; }
  bool parallel() const { return comm_ != MPI_COMM_NULL; }
  bool root() const { return root_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("HDF5 file " + file_ + ": " + what + " (" + hdf5_error_stack() + ")");
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void check(herr_t status, const char* what, const std::string& object) const {
    if (status < 0) fail(std::string(what) + " " + object);
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  bool root_ = true;
};

// One session with the file: opened (or created) by the constructor, closed
// with a checked H5Fclose by close(). H5F_CLOSE_SEMI makes H5Fclose fail if an
// object inside is still open, so a leaked handle cannot keep the file (and
// its lock) alive silently.
class Hdf5File {
 public:
  enum class Mode { create, append };

  Hdf5File(const Hdf5Errors& errors, Mode mode) : errors_(errors) {
    Handle access(errors_.check(H5Pcreate(H5P_FILE_ACCESS), "cannot create file access list for"), H5Pclose);
    errors_.check(H5Pset_fclose_degree(access.get(), H5F_CLOSE_SEMI), "cannot set close degree of", "file");
    if (errors_.parallel()) {
      // The collective writes' buffer on the aggregating rank (Open MPI's OMPIO: 32 MiB
      // by default, and touched as far as a field's rows go: the whole field on one
      // node). Each rank's rows are one contiguous block, so a buffer of 1 MiB costs
      // no write more than a few rounds, and rank 0 holds no more than the others.
      MPI_Info info = MPI_INFO_NULL;
      MPI_Info_create(&info);
      MPI_Info_set(info, "cb_buffer_size", "1048576");
      const herr_t set = H5Pset_fapl_mpio(access.get(), errors_.comm(), info);
      MPI_Info_free(&info);
      errors_.check(set, "cannot set MPI-IO for", "file");
    }
    if (mode == Mode::create) {
      file_ =
          Handle(errors_.check(H5Fcreate(errors_.file().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                               "cannot create file"),
                 H5Fclose);
    } else {
      file_ = Handle(open_for_append(access.get()), H5Fclose);
    }
  }

  hid_t get() const { return file_.get(); }

  void close() {
    const herr_t status = H5Fclose(file_.release());
    errors_.check(status, "cannot close", "file (an object inside is still open?)");
  }

 private:
  // A reader that holds the file open (h5py, h5dump, a ParaView session)
  // keeps HDF5 1.10's lock; such readers are short-lived, so wait a little
  // before turning it into a run failure.
  hid_t open_for_append(hid_t access) const {
    using namespace std::chrono_literals;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    for (;;) {
      const hid_t id = H5Fopen(errors_.file().c_str(), H5F_ACC_RDWR, access);
      if (id >= 0) return id;
      if (!std::filesystem::exists(errors_.file()))
        errors_.fail("cannot open file for writing: it no longer exists");
      if (std::chrono::steady_clock::now() >= deadline) {
        errors_.fail("cannot open file for writing for 10 s (another program holding it open?)");
      }
      H5Eclear2(H5E_DEFAULT);
      std::this_thread::sleep_for(100ms);
    }
  }

  const Hdf5Errors& errors_;
  Handle file_;
};

inline Handle create_group(const Hdf5Errors& errors, hid_t parent, const std::string& path) {
  return Handle(errors.check(H5Gcreate2(parent, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             "cannot create group " + path),
                H5Gclose);
}

// The group that gains one link per written step (/steps), made so that a step's
// link is one in-place change of one block of the file. Its links are stored
// "compactly", as messages of the group's own object header, and that header is
// sized at creation for `expected_links` links: adding a step then rewrites the
// header where it is, and nothing on disk that an earlier step's path goes through
// is moved, freed or split. (A group of the old format keeps its names in a local
// heap that is moved, and its old block freed and reused, each time the heap
// doubles, and in a B-tree whose nodes split: a kill inside that work left a
// file whose /steps could not be read, docs/stability.md "Interrupted and killed runs".)
// Tracking the links' creation order is what makes HDF5 use the link messages in a
// file of the earliest format (superblock 0, readable by every HDF5 reader).
// The estimate is capped at 4096 links (about 135 kB of header, rewritten with
// each step); past it the header grows by continuation blocks, and the links stay
// compact up to 65535.
inline Handle create_step_group(const Hdf5Errors& errors, hid_t parent, const std::string& path,
                                unsigned expected_links) {
  Handle properties(errors.check(H5Pcreate(H5P_GROUP_CREATE), "cannot create properties for " + path),
                    H5Pclose);
  const unsigned estimate = std::clamp(expected_links, 4U, 4096U);
  errors.check(H5Pset_link_creation_order(properties.get(), H5P_CRT_ORDER_TRACKED),
               "cannot set link creation order of", path);
  errors.check(H5Pset_link_phase_change(properties.get(), 65535, 65535), "cannot set link storage of", path);
  errors.check(H5Pset_est_link_info(properties.get(), estimate, 6), "cannot size the links of", path);
  return Handle(errors.check(H5Gcreate2(parent, path.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                             "cannot create group " + path),
                H5Gclose);
}

// Writes rows [begin, begin + count) of `dataset` (shape `dims`, rows along the
// first) from `data`: alone, or on many ranks collectively, each its own rows.
inline void write_rows(const Hdf5Errors& errors, hid_t dataset, const std::string& path,
                       const std::vector<hsize_t>& dims, hid_t memory_type, const void* data, hsize_t begin,
                       hsize_t count) {
  if (!errors.parallel() && begin == 0 && count == dims[0]) {
    errors.check(H5Dwrite(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset",
                 path);
    return;
  }
  Handle file_space(errors.check(H5Dget_space(dataset), "cannot get dataspace of " + path), H5Sclose);
  std::vector<hsize_t> offset(dims.size(), 0), block(dims);
  offset[0] = begin;
  block[0] = count;
  Handle memory_space;
  if (count == 0) {
    errors.check(H5Sselect_none(file_space.get()), "cannot select rows of", path);
    memory_space =
        Handle(errors.check(H5Screate(H5S_SCALAR), "cannot create dataspace for " + path), H5Sclose);
    errors.check(H5Sselect_none(memory_space.get()), "cannot select rows of", path);
  } else {
    errors.check(
        H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, offset.data(), nullptr, block.data(), nullptr),
        "cannot select rows of", path);
    memory_space =
        Handle(errors.check(H5Screate_simple(static_cast<int>(block.size()), block.data(), nullptr),
                            "cannot create dataspace for " + path),
               H5Sclose);
  }
  Handle transfer(errors.check(H5Pcreate(H5P_DATASET_XFER), "cannot create transfer list for " + path),
                  H5Pclose);
  if (errors.parallel())
    errors.check(H5Pset_dxpl_mpio(transfer.get(), H5FD_MPIO_COLLECTIVE), "cannot set collective writes of",
                 path);
  errors.check(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), transfer.get(), data),
               "cannot write dataset", path);
}

// The rows a process writes of a dataset that one rank holds whole (the mesh, the
// history: the same on every rank): all of them alone, or on the root rank.
inline std::pair<hsize_t, hsize_t> whole_rows(const Hdf5Errors& errors, hsize_t rows) {
  return {0, errors.root() ? rows : 0};
}

// Creates a fixed-size dataset `path` of shape `dims` and writes rows
// [rows.first, rows.first + rows.second) of it from `data` (by default all: the
// whole dataset, written by the root rank on many ranks).
inline void write_dataset(const Hdf5Errors& errors, hid_t file, const std::string& path,
                          const std::vector<hsize_t>& dims, hid_t file_type, hid_t memory_type,
                          const void* data, std::optional<std::pair<hsize_t, hsize_t>> rows = std::nullopt) {
  Handle space(errors.check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                            "cannot create dataspace for " + path),
               H5Sclose);
  Handle dataset(errors.check(H5Dcreate2(file, path.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                         H5P_DEFAULT),
                              "cannot create dataset " + path),
                 H5Dclose);
  const auto [begin, count] = rows ? *rows : whole_rows(errors, dims[0]);
  write_rows(errors, dataset.get(), path, dims, memory_type, data, begin, count);
}

// An empty float64 series (0,) extendable without limit, chunked.
// An extendable series of rows of `columns` doubles: (H,) for one column, (H, columns) else.
inline void create_series(const Hdf5Errors& errors, hid_t file, const std::string& path,
                          hsize_t columns = 1) {
  const int rank = columns == 1 ? 1 : 2;
  const hsize_t dims[2] = {0, columns};
  const hsize_t max_dims[2] = {H5S_UNLIMITED, columns};
  const hsize_t chunk[2] = {series_chunk_rows, columns};
  Handle space(errors.check(H5Screate_simple(rank, dims, max_dims), "cannot create dataspace for " + path),
               H5Sclose);
  Handle properties(errors.check(H5Pcreate(H5P_DATASET_CREATE), "cannot create properties for " + path),
                    H5Pclose);
  errors.check(H5Pset_chunk(properties.get(), rank, chunk), "cannot set chunking of", path);
  Handle dataset(errors.check(H5Dcreate2(file, path.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                         properties.get(), H5P_DEFAULT),
                              "cannot create dataset " + path),
                 H5Dclose);
}

// Appends `values` (rows of `columns` doubles) to the series `path`, which holds `rows_on_disk` rows.
inline void append_series(const Hdf5Errors& errors, hid_t file, const std::string& path, hsize_t rows_on_disk,
                          const std::vector<double>& values, hsize_t columns = 1) {
  const int rank = columns == 1 ? 1 : 2;
  Handle dataset(errors.check(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "cannot open dataset " + path),
                 H5Dclose);
  const hsize_t rows = values.size() / columns;
  const hsize_t new_size[2] = {rows_on_disk + rows, columns};
  const hsize_t offset[2] = {rows_on_disk, 0};
  errors.check(H5Dset_extent(dataset.get(), new_size), "cannot extend dataset", path);
  std::vector<hsize_t> dims{new_size[0]};
  if (rank == 2) dims.push_back(columns);
  const hsize_t written = errors.parallel() && !errors.root() ? 0 : rows;
  write_rows(errors, dataset.get(), path, dims, H5T_NATIVE_DOUBLE, values.data(), offset[0], written);
}

inline void write_scalar_attribute(const Hdf5Errors& errors, hid_t object, const std::string& object_path,
                                   const char* name, hid_t file_type, hid_t memory_type, const void* value) {
  const std::string what = object_path + "@" + name;
  Handle space(errors.check(H5Screate(H5S_SCALAR), "cannot create dataspace for " + what), H5Sclose);
  Handle attribute(errors.check(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                                "cannot create attribute " + what),
                   H5Aclose);
  errors.check(H5Awrite(attribute.get(), memory_type, value), "cannot write attribute", what);
}

}  // namespace exdyn::output::hdf5
