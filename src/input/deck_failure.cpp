// The deck's material failure: `failure` of a plastic material (docs/input.md).
#include <cmath>

#include "input/deck_validator.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input::deck {

void DeckValidator::failure(const YAML::Node& body, const std::string& path,
                            MaterialOptions& material) const {
  const YAML::Node node = optional(body, "failure");
  if (!node.IsDefined()) return;
  const std::string failure_path = child_path(path, "failure");
  if (material.model == MaterialModel::linear_elastic)
    fail(node, failure_path,
         "a linear_elastic material does not fail: failure needs a plastic model (elastic_plastic or "
         "johnson_cook)");
  const std::string expected = "{plastic_strain: eps_f} or {johnson_cook: {D1, D2, D3, D4, D5}}";
  if (!node.IsMap() || node.size() == 0)
    fail(node, failure_path, "expected " + expected + ", got " + describe(node));
  check_map(node, failure_path, {"plastic_strain", "johnson_cook"});
  const YAML::Node strain = optional(node, "plastic_strain");
  const YAML::Node jc = optional(node, "johnson_cook");
  if (strain.IsDefined() && jc.IsDefined())
    fail(jc, child_path(failure_path, "johnson_cook"),
         "give either plastic_strain or johnson_cook, not both");
  if (strain.IsDefined()) {
    material.failure = FailureModel::plastic_strain;
    material.failure_strain = number_where(strain, child_path(failure_path, "plastic_strain"),
                                           "a number > 0 (the failure plastic strain eps_f)", positive);
    return;
  }
  const std::string jc_path = child_path(failure_path, "johnson_cook");
  if (!jc.IsMap()) fail(jc, jc_path, "expected a map {D1, D2, D3, D4, D5}, got " + describe(jc));
  check_map(jc, jc_path, {"D1", "D2", "D3", "D4", "D5"});
  material.failure = FailureModel::johnson_cook;
  for (std::size_t k = 0; k < 5; ++k) {
    const std::string key = "D" + std::to_string(k + 1);
    const YAML::Node value = k < 4 ? required(jc, jc_path, key) : optional(jc, key);
    if (value.IsDefined()) material.failure_d[k] = number(value, child_path(jc_path, key), "a number");
  }
  // eps_f = (D1 + D2 exp(D3 s))(1 + D4 ln r): each factor is monotone, so it is positive
  // over the range used where it is at both ends.
  const auto& d = material.failure_d;
  for (const double triaxiality : {failure_triaxiality_min, failure_triaxiality_max}) {
    const double factor = d[0] + d[1] * std::exp(d[2] * triaxiality);
    if (!(factor > 0.0))
      fail(jc["D1"], child_path(jc_path, "D1"),
           "D1 + D2 exp(D3 sigma*) = " + format_number(factor) +
               " at the triaxiality sigma* = " + format_number(triaxiality) +
               ": the failure strain must be > 0 for sigma* in [-1/3, 1.5], where damage is counted");
  }
  const double rate_factor = 1.0 + d[3] * std::log(failure_rate_ratio_max);
  if (!(rate_factor > 0.0))
    fail(jc["D4"], child_path(jc_path, "D4"),
         "1 + D4 ln(eps_dot_p / eps_dot_0) = " + format_number(rate_factor) +
             " at the rate ratio 1e12: the failure strain must be > 0 for rate ratios up to 1e12");
}

}  // namespace exdyn::input::deck
