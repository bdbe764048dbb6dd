// How the chunks of the elements are dealt to the MPI ranks (`exdyn run --partition`;
// ranks/partition.cpp, docs/parallel.md).
#pragma once

namespace exdyn::solver {

enum class Partitioning {
  bisection,  // recursive coordinate bisection of the chunk centroids (the default)
  metis,      // METIS's k-way partition of the graph of chunks that share nodes
};

}  // namespace exdyn::solver
