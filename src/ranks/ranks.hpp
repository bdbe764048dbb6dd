// What the time loop (solver/) calls of the many-rank code: its one face.
//
// On one process none of it runs: a Decomposition of one rank holds no exchange, and
// the loop's passes take their one-process paths. On many ranks (docs/parallel.md):
//  - setup:   set_up_rank builds this rank's part alone (RankSetup: its model, its
//             decomposition, its contact faces); build_contact runs on those faces
//             with contact_scope, globalize_contact renumbers what it built, and
//             distribute_contact deals the contact's points and segments;
//             mesh_rows gives the output the rows of the mesh this rank writes;
//  - a step:  add_forces_across_ranks (the running sums of the shared nodes' forces),
//             run_distributed_contact (each rank its own slave points);
//  - output:  rows_of (the owners' values to the ranks that write their rows);
//  - figures: halo_figures and contact_share_figures for the summary.
// Every one of them is collective over the decomposition's communicator.
#pragma once

#include "ranks/decomposition.hpp"        // Decomposition, LocalRun, the force exchange, the output rows
#include "ranks/distributed_contact.hpp"  // distribute_contact, run_distributed_contact, the figures
#include "ranks/partitioning.hpp"         // Partitioning
#include "ranks/rank_setup.hpp"           // set_up_rank, contact_scope, globalize_contact
