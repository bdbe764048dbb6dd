// Names of the local contact search vocabulary, shared by the deck reader, the
// `exdyn project` cases reader and the local search library. Header-only, so
// that input/ can validate names without linking the contact library.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <utility>

namespace exdyn::contact {

// Master segment: bilinear 4-node or quadratic serendipity 8-node quadrilateral.
enum class SegmentType { quad4, quad8 };

// Local search methods of the seed paper, plus `robust` (docs/local-search.md).
enum class SearchMethod {
  newton,            // Newton-Raphson, eq. 8
  lsp,               // least-squares projection (Gauss-Newton), eq. 14
  steepest_descent,  // analytic step length, eq. 19
  broyden,           // eq. 21-22
  bfgs,              // eq. 23-24
  dfp,               // eq. 25-27
  simplex,           // Nelder-Mead
  hybrid,            // simplex for the coarse search, then BFGS
  robust             // grid seed, damped Newton, active set on the bounds
};

// Where a projection starts.
enum class InitialGuess {
  lsp,       // one least-squares step from the centre
  center,    // (0, 0)
  previous,  // the pair's point from the last step (contact runs only)
};

inline constexpr std::array<std::pair<SegmentType, std::string_view>, 2> segment_type_names{{
    {SegmentType::quad4, "quad4"},
    {SegmentType::quad8, "quad8"},
}};

inline constexpr std::array<std::pair<SearchMethod, std::string_view>, 9> search_method_names{{
    {SearchMethod::newton, "newton"},
    {SearchMethod::lsp, "lsp"},
    {SearchMethod::steepest_descent, "steepest_descent"},
    {SearchMethod::broyden, "broyden"},
    {SearchMethod::bfgs, "bfgs"},
    {SearchMethod::dfp, "dfp"},
    {SearchMethod::simplex, "simplex"},
    {SearchMethod::hybrid, "hybrid"},
    {SearchMethod::robust, "robust"},
}};

inline constexpr std::array<std::pair<InitialGuess, std::string_view>, 3> initial_guess_names{{
    {InitialGuess::lsp, "lsp"},
    {InitialGuess::center, "center"},
    {InitialGuess::previous, "previous"},
}};

template <class Enum, std::size_t N>
constexpr std::string_view name_of(const std::array<std::pair<Enum, std::string_view>, N>& table,
                                   Enum value) {
  for (const auto& [v, n] : table)
    if (v == value) return n;
  return "?";
}

template <class Enum, std::size_t N>
constexpr std::optional<Enum> from_name(const std::array<std::pair<Enum, std::string_view>, N>& table,
                                        std::string_view text) {
  for (const auto& [v, n] : table)
    if (n == text) return v;
  return std::nullopt;
}

constexpr std::string_view name(SegmentType t) { return name_of(segment_type_names, t); }
constexpr std::string_view name(SearchMethod m) { return name_of(search_method_names, m); }
constexpr std::string_view name(InitialGuess g) { return name_of(initial_guess_names, g); }

}  // namespace exdyn::contact
