// Many processes (docs/parallel.md): the MPI session and the few collective
// operations the solver and the writer need, on one communicator.
//
// A process started by mpirun (OpenMPI's or another launcher's environment) joins
// MPI_COMM_WORLD; a process started without it does not initialise MPI at all and is
// rank 0 of 1, so that `exdyn run` and every test run as before, with no launcher
// and nothing of MPI's start-up cost. MPI is called from the main thread only
// (MPI_THREAD_FUNNELED): the OpenMP threads of a rank never talk to other ranks.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace exdyn::mpi {

// The ranks of one run. Without MPI (comm = MPI_COMM_NULL) it is rank 0 of 1 and
// every operation below is the identity.
struct Communicator {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  int size = 1;
  int ranks_on_this_machine = 1;  // the ranks that share this rank's machine (its cores)

  bool distributed() const { return size > 1; }
  bool root() const { return rank == 0; }
};

// True when a launcher started this process as one rank of a job: OpenMPI's mpirun
// (OMPI_COMM_WORLD_SIZE), a PMIx launcher (PMIX_RANK) or an MPICH-style one (PMI_RANK).
inline bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

// Initialises MPI for the process's lifetime when launched by mpirun (else does
// nothing) and finalises it at the end. One per process, in main.
class Session {
 public:
  Session() {
    if (!launched_by_mpirun()) return;
    int provided = MPI_THREAD_SINGLE;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
      throw std::runtime_error("MPI could not start (MPI_Init_thread failed): check the mpirun command");
    initialised_ = true;
    if (provided < MPI_THREAD_FUNNELED)
      throw std::runtime_error("MPI gives no thread support (MPI_THREAD_FUNNELED): exdyn's threads need it");
    // Errors come back as codes and are turned into exceptions with a message (check).
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    world_.comm = MPI_COMM_WORLD;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_.size);
    MPI_Comm machine = MPI_COMM_NULL;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine) ==
        MPI_SUCCESS) {
      MPI_Comm_size(machine, &world_.ranks_on_this_machine);
      MPI_Comm_free(&machine);
    }
  }
  ~Session() {
    if (initialised_) MPI_Finalize();
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const Communicator& world() const { return world_; }
  // Ends every rank at once with `code` (an error that not every rank saw).
  void abort(int code) const {
    if (initialised_) MPI_Abort(MPI_COMM_WORLD, code);
  }

 private:
  bool initialised_ = false;
  Communicator world_;
};

// Throws std::runtime_error naming the call when an MPI call failed.
inline void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string("MPI: ") + what +
                           " failed: " + std::string(text, std::size_t(length)));
}

// Every rank's `count` values, rank after rank (the same array on every rank, so
// sums formed from it in rank order are the same bits everywhere: unlike
// MPI_Allreduce, whose order of additions may differ from rank to rank).
inline std::vector<double> all_gather(const Communicator& c, const double* values, int count) {
  std::vector<double> all(std::size_t(count) * std::size_t(c.size));
  if (!c.distributed()) {
    std::copy(values, values + count, all.begin());
    return all;
  }
  check(MPI_Allgather(values, count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, c.comm), "MPI_Allgather");
  return all;
}

// Every rank's `values` (any number each), rank after rank, on every rank.
template <class T>
std::vector<T> all_gather_varying(const Communicator& c, const std::vector<T>& values) {
  static_assert(std::is_same_v<T, std::uint32_t> || std::is_same_v<T, double>);
  const MPI_Datatype type = std::is_same_v<T, double> ? MPI_DOUBLE : MPI_UINT32_T;
  const int mine = static_cast<int>(values.size());
  std::vector<int> counts(std::size_t(c.size)), offsets(std::size_t(c.size), 0);
  check(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, c.comm), "MPI_Allgather of the counts");
  for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<T> all(std::size_t(offsets.back() + counts.back()));
  check(MPI_Allgatherv(values.data(), mine, type, all.data(), counts.data(), offsets.data(), type, c.comm),
        "MPI_Allgatherv");
  return all;
}

// The message of the lowest rank whose `local` is not empty ("" if none): every rank
// gets it, so all stop together, with the words of the rank that saw the fault.
inline std::string first_message(const Communicator& c, const std::string& local) {
  if (!c.distributed()) return local;
  const int length = static_cast<int>(local.size());
  std::vector<int> lengths(std::size_t(c.size));
  check(MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, c.comm), "MPI_Allgather");
  for (int r = 0; r < c.size; ++r) {
    if (lengths[std::size_t(r)] == 0) continue;
    std::string message(std::size_t(lengths[std::size_t(r)]), '\0');
    if (r == c.rank) message = local;
    check(MPI_Bcast(message.data(), lengths[std::size_t(r)], MPI_CHAR, r, c.comm), "MPI_Bcast");
    return message;
  }
  return {};
}

// The smallest of every rank's value (exact: the same on every rank).
inline double min(const Communicator& c, double value) {
  if (!c.distributed()) return value;
  double result = value;
  check(MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MIN, c.comm), "MPI_Allreduce");
  return result;
}

// The largest of every rank's value.
inline double max(const Communicator& c, double value) {
  if (!c.distributed()) return value;
  double result = value;
  check(MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, c.comm), "MPI_Allreduce");
  return result;
}

}  // namespace exdyn::mpi
