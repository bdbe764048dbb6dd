// The three kinds of error (see docs/theory.md, "Errors"):
//  - InputError: bad input or bad usage (exit status 2). Names the file, line,
//    column and key path of a deck when it has them.
//  - RunFailure: a physical failure during a run (exit status 1). Names what,
//    where (element, node, contact pair) and when (step, time).
//  - a broken invariant: EXDYN_ASSERT, active in debug builds only.
// One try/catch in main() turns the first two into a message and an exit status.
#pragma once

#include <cassert>
#include <stdexcept>
#include <string>

namespace exdyn {

// Where in an input file a value stands (1-based line and column; 0 = unknown).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

class InputError : public std::runtime_error {
 public:
  // A usage error or an error with no position in a file.
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // "deck.yaml:12:5: parts[1].elements: expected a list of 3 integers >= 1, got ..."
  InputError(const SourceLocation& where, const std::string& key_path, const std::string& message)
      : std::runtime_error(format(where, key_path, message)), location_(where), key_path_(key_path) {}

  const SourceLocation& location() const { return location_; }
  const std::string& key_path() const { return key_path_; }

 private:
  static std::string format(const SourceLocation& where, const std::string& key_path,
                            const std::string& message) {
    std::string text = where.file.empty() ? std::string("<input>") : where.file;
    if (where.line > 0) {
      text += ":" + std::to_string(where.line);
      if (where.column > 0) text += ":" + std::to_string(where.column);
    }
    text += ": ";
    if (!key_path.empty()) text += key_path + ": ";
    return text + message;
  }
  SourceLocation location_;
  std::string key_path_;
};

class RunFailure : public std::runtime_error {
 public:
  RunFailure(const std::string& message, long step, double time)
      : std::runtime_error(message), step_(step), time_(time) {}
  long step() const { return step_; }
  double time() const { return time_; }

 private:
  long step_;
  double time_;
};

// Not an error but the fourth ending of a run (exit status 3): it stopped on request
// (SIGTERM, SIGINT, --wall-limit) after writing a checkpoint it can go on from.
class RunStopped : public std::runtime_error {
 public:
  RunStopped(const std::string& message, long step) : std::runtime_error(message), step_(step) {}
  long step() const { return step_; }

 private:
  long step_;
};

}  // namespace exdyn

#define EXDYN_ASSERT(condition) assert(condition)
