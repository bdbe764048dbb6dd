// The memory a run of a deck needs, estimated from its node and element counts
// before anything of that size is allocated (docs/input.md, "Mesh size"), so that
// `elements: [100000, 100000, 100000]` is refused as bad input instead of
// failing somewhere inside the allocator.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "input/options.hpp"

namespace exdyn::solver {

// Bytes a run holds per node and per element: the arrays of the mesh, the model,
// the time loop's state and the result writer, slightly conservative (the
// writer's temporary 64-bit connectivity is counted as if it lived on).
// memory_estimate.cpp checks the counts against the types they come from.
//   per node, 42 doubles: reference coordinates 3 (mesh), mass and 1/mass 2 (model);
//     u, v, a, f_int, f_contact and the previous f_contact 18 (the nodal update works
//     in place), the fixed-component flags 3 bytes counted as 1 double, gap and previous gap
//     2 (time loop); v at the step 3 (step writer); the frame of a written step,
//     displacement, velocity, acceleration and contact force as (N, 3) rows and the
//     gap, 13 (HDF5 writer: the copy its thread writes from)
//   per element, 212 B besides the element block's reference data: 8 node ids 32 B
//     and the part index 4 B (mesh); stress 6 doubles and von Mises 1 (time loop,
//     step writer) and their copies in the frame 7; the int64 connectivity written to
//     HDF5 64 B
//   reference data per element (hex8_family.cpp): the parallelepiped kernels' 10
//     doubles (hex8) or 34 (hex8r) for a regular box; a distorted part (perturbation)
//     runs the general kernels, 81 doubles (hex8) or 59 (hex8r; its law kernels 36 or
//     46, and the assumed-strain hourglass state, 2 x 25, is not counted, as the
//     point states of a plastic law are not)
//   20-node parts (hex20_family.cpp): 20 node ids, the int64 connectivity, and the
//     general reference data while the block is built, 271 doubles (hex20) or 81
//     (hex20r); a part has about 4 nodes per element
// Not counted: arrays of the contact faces and fixed faces (they grow with the
// surface, not the volume) and the program itself; but a part in a `surface: all` that
// follows erosion (docs/contact.md, "Faces that erosion opens") holds every face its
// bricks share in the contact, about 6 segments an element: bytes_per_opening_element
// more per element, measured as the peak resident size of input/punch_through.yaml's
// plate at 24 x 24 x 8 and 48 x 48 x 8 bricks less the same deck's without `failure`
// (2.4 KiB an element at both).
inline constexpr std::uint64_t bytes_per_node = 42 * 8;
inline constexpr std::uint64_t bytes_per_opening_element = 3 * 1024;
inline constexpr std::uint64_t bytes_per_element_besides_reference = 32 + 4 + 14 * 8 + 64;

// Bytes per element of one part: 300 for a regular box, 860 (hex8) or 500 (hex8r) distorted.
std::uint64_t bytes_per_element(const input::PartOptions& part);

struct MemoryEstimate {
  // Totals over the parts; UINT64_MAX when a count does not fit 64 bits.
  std::uint64_t nodes = 0;
  std::uint64_t elements = 0;
  // Sum over the parts of nodes * bytes_per_node + elements * bytes_per_element,
  // in a double so that the counts of an absurd deck (up to 2^93) do not overflow.
  double bytes = 0.0;
};

MemoryEstimate estimate_memory(const input::Deck& deck);

// MemAvailable of a /proc/meminfo file, in bytes; empty when the file cannot be
// read or has no such line.
std::optional<std::uint64_t> available_memory(const std::string& meminfo_path = "/proc/meminfo");

// The ranks of a run and how many of them share this machine: a run on many ranks
// (ranks/rank_setup.hpp) needs about the model's memory times ranks_here / ranks on
// this machine (each rank its part and a halo of one element; boxes, cylinders and
// balls are set up by numbers). An imported part is read and held whole by rank 0
// alone while it sets up; it is not counted here, its size is known only once it is
// read.
struct MachineShare {
  int ranks = 1, ranks_here = 1;
};

// Throws InputError naming every part's element counts, the estimate and the
// memory available when the mesh has more nodes than 32-bit node indices can
// number (4294967295) or more elements than 2147483647, or when the estimate (this
// machine's share of it) exceeds `available_bytes` (no memory check when it is empty).
void check_mesh_size(const input::Deck& deck, std::optional<std::uint64_t> available_bytes,
                     MachineShare share = {});

// The same with the machine's MemAvailable (/proc/meminfo): build_model's first step.
void check_mesh_size(const input::Deck& deck, MachineShare share = {});

}  // namespace exdyn::solver
