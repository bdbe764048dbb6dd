#include "output/summary.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "output/atomic_file.hpp"

namespace exdyn::output {
namespace {

// ordered_json keeps the keys in the order of ../shared/spec/output.md, so a
// person reading the file finds them where the spec shows them.
using Json = nlohmann::ordered_json;

// JSON has no NaN or infinity. A non-finite value (a diverged energy, a rate
// of a run that never started its time loop) is written as null, which every
// JSON reader accepts and no reader can mistake for a number.
Json number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

Json to_json(const RunSummary& s) {
  Json phases;
  phases["element_forces"] = number(s.phase_seconds.element_forces);
  phases["contact_global_search"] = number(s.phase_seconds.contact_global_search);
  phases["contact_local_search"] = number(s.phase_seconds.contact_local_search);
  phases["contact_forces"] = number(s.phase_seconds.contact_forces);
  phases["time_integration"] = number(s.phase_seconds.time_integration);
  phases["output"] = number(s.phase_seconds.output);
  phases["guards"] = number(s.phase_seconds.guards);
  phases["contact_segmentation"] = number(s.phase_seconds.contact_segmentation);

  Json energy;
  energy["initial_total"] = number(s.energy.initial_total);
  energy["final_total"] = number(s.energy.final_total);
  energy["max_relative_error"] = number(s.energy.max_relative_error);
  energy["internal"] = number(s.energy.internal);
  energy["hourglass"] = number(s.energy.hourglass);
  energy["plastic_work"] = number(s.energy.plastic_work);
  energy["eroded"] = number(s.energy.eroded);
  energy["eroded_elements"] = s.energy.eroded_elements;

  const auto figures = [](const ContactFigures& f) {
    Json json;
    json["projections"] = f.projections;
    json["mean_iterations"] = number(f.mean_iterations);
    json["max_iterations"] = f.max_iterations;
    json["not_converged"] = f.not_converged;
    json["saddle_points"] = f.saddle_points;
    json["max_penetration_over_h"] = number(f.max_penetration_over_h);
    json["penalty_stiffness"] = number(f.penalty_stiffness);
    json["fallbacks"] = f.fallbacks;  // ours, after the spec's
    return json;
  };
  Json contact = figures(s.contact);
  Json pairs = Json::object();
  for (const ContactPairSummary& pair : s.contact.pairs) {
    Json json = figures(pair.figures);
    json["slave_points"] = pair.slave_points;
    json["method"] = pair.method;
    json["local_search_seconds"] = number(pair.local_search_seconds);
    json["segmentation_seconds"] = number(pair.segmentation_seconds);
    json["max_force"] = number(pair.max_force);
    json["friction_work"] = number(pair.friction_work);
    json["peak_normal_force_sum"] = number(pair.peak_normal_force_sum);
    json["points_in_contact_at_peak"] = pair.points_in_contact_at_peak;
    pairs[pair.name] = std::move(json);
  }
  contact["pairs"] = std::move(pairs);
  Json walls = Json::object();
  for (const WallSummary& wall : s.contact.walls) {
    Json json;
    json["slave_points"] = wall.slave_points;
    json["max_force"] = number(wall.max_force);
    json["max_penetration_over_h"] = number(wall.max_penetration_over_h);
    json["penalty_stiffness"] = number(wall.penalty_stiffness);
    json["friction_work"] = number(wall.friction_work);
    walls[wall.name] = std::move(json);
  }
  contact["rigid_walls"] = std::move(walls);

  Json mesh;
  mesh["nodes"] = s.nodes;
  mesh["elements"] = s.elements;

  Json j;
  j["name"] = s.name;
  j["status"] = s.status;
  j["message"] = s.message;
  j["exdyn_version"] = s.exdyn_version;
  j["threads"] = s.threads;
  j["mesh"] = std::move(mesh);
  j["steps"] = s.steps;
  j["dt"] = number(s.dt);
  j["end_time"] = number(s.end_time);
  j["wall_seconds"] = number(s.wall_seconds);
  j["element_cycles_per_second"] = number(s.element_cycles_per_second);
  j["phase_seconds"] = std::move(phases);
  j["energy"] = std::move(energy);
  j["contact"] = std::move(contact);
  Json mpi;
  mpi["ranks"] = s.ranks;
  mpi["shared_nodes"] = s.mpi.shared_nodes;  // ours, after the spec's key
  mpi["messages_per_step"] = s.mpi.messages_per_step;
  mpi["bytes_per_step"] = number(s.mpi.bytes_per_step);
  mpi["contact_nodes"] = s.mpi.contact_nodes;
  mpi["exchange_seconds"] = number(s.mpi.exchange_seconds);
  mpi["partition"] = s.mpi.partition;
  mpi["edge_cut"] = s.mpi.edge_cut;
  mpi["weigh"] = s.mpi.weigh;
  mpi["setup"] = s.mpi.setup;
  Json per_rank = Json::object();
  auto column = [&](const char* key, double output::MpiSummary::Rank::*member) {
    Json values = Json::array();
    for (const auto& r : s.mpi.per_rank) values.push_back(number(r.*member));
    per_rank[key] = std::move(values);
  };
  column("peak_resident_mb", &MpiSummary::Rank::peak_resident_mb);
  column("contact_nodes", &MpiSummary::Rank::contact_nodes);
  column("contact_points", &MpiSummary::Rank::contact_points);
  column("contact_segments", &MpiSummary::Rank::contact_segments);
  column("ghost_segments", &MpiSummary::Rank::ghost_segments);
  column("ghost_nodes", &MpiSummary::Rank::ghost_nodes);
  column("contact_messages_per_step", &MpiSummary::Rank::contact_messages_per_step);
  column("contact_bytes_per_step", &MpiSummary::Rank::contact_bytes_per_step);
  column("force_messages_per_step", &MpiSummary::Rank::force_messages_per_step);
  column("force_bytes_per_step", &MpiSummary::Rank::force_bytes_per_step);
  column("wait_seconds", &MpiSummary::Rank::wait_seconds);
  column("element_seconds", &MpiSummary::Rank::element_seconds);
  column("contact_seconds", &MpiSummary::Rank::contact_seconds);
  mpi["per_rank"] = std::move(per_rank);
  j["mpi"] = std::move(mpi);
  Json guards;  // ours, after the spec's keys
  guards["inversion_passes"] = s.guard_checks.inversion_passes;
  guards["largest_energy_growth"] = number(s.guard_checks.largest_energy_growth);
  j["guards"] = std::move(guards);
  j["isa"] = s.isa;  // after the spec's keys, as every addition
  j["dt_min"] = number(s.dt_min > 0.0 ? s.dt_min : s.dt);
  j["warnings"] = s.warnings;
  if (s.restart.from_step >= 0) {
    Json restart;
    restart["from_step"] = s.restart.from_step;
    restart["checkpoint"] = s.restart.checkpoint;
    j["restart"] = std::move(restart);
  }
  if (s.checkpoints.written > 0) {
    Json checkpoints;
    checkpoints["written"] = s.checkpoints.written;
    checkpoints["seconds"] = number(s.checkpoints.seconds);
    checkpoints["largest_seconds"] = number(s.checkpoints.largest_seconds);
    checkpoints["bytes"] = number(s.checkpoints.bytes);
    checkpoints["last"] = s.checkpoints.last;
    j["checkpoints"] = std::move(checkpoints);
  }
  return j;
}

}  // namespace

void write_summary(const std::string& path, const RunSummary& summary) {
  // A failure message may quote bytes of the deck that are not UTF-8; replace
  // them (U+FFFD) rather than throw, because the summary of a failed run must
  // still be written.
  const std::string text =
      to_json(summary).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, {std::string_view(text)});
}

}  // namespace exdyn::output
