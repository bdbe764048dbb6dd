#include "app/project_command.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "common/errors.hpp"
#include "contact/local_search.hpp"
#include "input/project_cases.hpp"

namespace exdyn::app {
namespace {

using contact::SearchMethod;
using contact::Xi;

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

std::vector<SearchMethod> parse_methods(const std::string& text) {
  std::vector<SearchMethod> methods;
  if (trim(text) == "all") {
    for (const auto& [method, name] : contact::search_method_names) methods.push_back(method);
    return methods;
  }
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string name = trim(
        std::string_view(text).substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    const auto method = contact::from_name(contact::search_method_names, name);
    if (!method) {
      std::string known;
      for (const auto& entry : contact::search_method_names)
        known += std::string(known.empty() ? "" : ", ") + std::string(entry.second);
      throw InputError("--method: unknown method '" + name + "' (expected all or one or more of " + known +
                       ")");
    }
    methods.push_back(*method);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return methods;
}

// Shortest round-trip text of a number (for "a;b" labels).
std::string shortest(double value) {
  std::array<char, 64> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value).ptr;
  return std::string(buffer.data(), end);
}

std::string full_precision(double value) {
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.17g", value);
  return buffer.data();
}

// One starting point: its label and, for lsp, no point (computed per case).
struct Guess {
  std::string label;
  std::optional<Xi> xi;  // nullopt: one LSP step from the centre
};

std::optional<std::vector<Guess>> parse_guesses(const std::string& text) {
  const std::string value = trim(text);
  if (value.empty()) return std::nullopt;  // the case's own, or lsp
  const std::vector<Guess> corners{
      {"corner1", Xi{-1, -1}}, {"corner2", Xi{1, -1}}, {"corner3", Xi{1, 1}}, {"corner4", Xi{-1, 1}}};
  if (value == "lsp") return std::vector<Guess>{{"lsp", std::nullopt}};
  if (value == "center" || value == "centre") return std::vector<Guess>{{"center", Xi{0, 0}}};
  if (value == "corners") return corners;
  if (value == "all") {
    std::vector<Guess> all{{"lsp", std::nullopt}, {"center", Xi{0, 0}}};
    all.insert(all.end(), corners.begin(), corners.end());
    return all;
  }
  const std::size_t separator = value.find_first_of(",;");
  const auto number = [&](std::string_view part) {
    const std::string t = trim(part);
    double x = 0.0;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (t.empty() || error != std::errc() || end != t.data() + t.size() || !std::isfinite(x)) {
      throw InputError("--initial-guess: expected lsp, center, corners, all or two numbers a,b; got '" +
                       text + "'");
    }
    return x;
  };
  if (separator == std::string::npos)
    throw InputError("--initial-guess: expected lsp, center, corners, all or two numbers a,b; got '" + text +
                     "'");
  const Xi xi{number(std::string_view(value).substr(0, separator)),
              number(std::string_view(value).substr(separator + 1))};
  return std::vector<Guess>{{shortest(xi[0]) + ";" + shortest(xi[1]), xi}};
}

contact::Segment to_segment(const input::ProjectCase& c) {
  contact::Segment segment;
  segment.type = c.segment;
  for (std::size_t i = 0; i < c.nodes.size() && i < segment.nodes.size(); ++i)
    segment.nodes[i] = {c.nodes[i][0], c.nodes[i][1], c.nodes[i][2]};
  return segment;
}

// Wall time of one projection (nanoseconds): batches of repetitions, each of
// at least min_seconds / 5, and the least average over 5 batches (the least
// disturbed by other work on the machine). min_seconds = 0: one run.
double time_projection(contact::ProjectFn fn, const contact::Segment& segment, const contact::Vec3& point,
                       Xi xi0, const contact::ProjectionSettings& settings, double min_seconds) {
  using Clock = std::chrono::steady_clock;
  constexpr int batches = 5;
  volatile double sink = 0.0;
  const auto run_batch = [&](long repetitions) {
    const auto start = Clock::now();
    for (long k = 0; k < repetitions; ++k) sink = sink + fn(segment, point, xi0, settings).xi[0];
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const double batch_seconds = min_seconds / batches;
  long repetitions = 1;
  double seconds = run_batch(repetitions);
  while (seconds < batch_seconds && repetitions < (1L << 30)) {
    const double factor = seconds > 0.0 ? 1.2 * batch_seconds / seconds : 10.0;
    repetitions = std::max(repetitions * 2,
                           static_cast<long>(static_cast<double>(repetitions) * std::min(factor, 1000.0)));
    seconds = run_batch(repetitions);
  }
  double best = seconds;
  if (min_seconds > 0.0)
    for (int b = 1; b < batches; ++b) best = std::min(best, run_batch(repetitions));
  return 1.0e9 * best / static_cast<double>(repetitions);
}

}  // namespace

void run_project_command(const ProjectCommandOptions& options, std::ostream& out) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw InputError("--tolerance: expected a number > 0, got " + full_precision(options.tolerance));
  if (options.max_iterations < 1)
    throw InputError("--max-iterations: expected an integer >= 1, got " +
                     std::to_string(options.max_iterations));
  if (!(options.timing_seconds >= 0.0)) throw InputError("timing: expected seconds >= 0");
  const std::vector<SearchMethod> methods = parse_methods(options.methods);
  const std::optional<std::vector<Guess>> given_guesses = parse_guesses(options.initial_guess);
  const std::vector<input::ProjectCase> cases = input::read_project_cases(options.cases_file);

  out << "id,method,initial_guess,xi1,xi2,converged,iterations,evaluations,stationary,inside,distance,gap,"
         "nanoseconds\n";
  for (const input::ProjectCase& c : cases) {
    const contact::Segment segment = to_segment(c);
    const contact::Vec3 point{c.point[0], c.point[1], c.point[2]};
    std::vector<Guess> guesses;
    if (given_guesses) {
      guesses = *given_guesses;
    } else if (c.initial_guess) {
      const Xi xi{(*c.initial_guess)[0], (*c.initial_guess)[1]};
      guesses = {{shortest(xi[0]) + ";" + shortest(xi[1]), xi}};
    } else {
      guesses = {{"lsp", std::nullopt}};
    }
    for (const SearchMethod method : methods) {
      contact::ProjectionSettings settings;
      settings.method = method;
      settings.tolerance = options.tolerance;
      settings.max_iterations = options.max_iterations;
      const contact::ProjectFn fn = contact::select_method(method);
      for (const Guess& guess : guesses) {
        const Xi xi0 = guess.xi ? *guess.xi : contact::initial_guess_lsp(segment, point);
        const contact::ProjectionResult r = fn(segment, point, xi0, settings);
        const double nanoseconds = time_projection(fn, segment, point, xi0, settings, options.timing_seconds);
        std::array<char, 64> ns{};
        std::snprintf(ns.data(), ns.size(), "%.1f", nanoseconds);
        out << c.id << ',' << contact::name(method) << ',' << guess.label << ',' << full_precision(r.xi[0])
            << ',' << full_precision(r.xi[1]) << ',' << (r.converged ? 1 : 0) << ',' << r.iterations << ','
            << r.evaluations << ',' << contact::name(r.stationary) << ',' << (r.inside ? 1 : 0) << ','
            << full_precision(r.distance) << ',' << full_precision(r.gap) << ',' << ns.data() << '\n';
      }
    }
  }
}

}  // namespace exdyn::app
