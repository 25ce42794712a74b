#pragma once
// One error type for bad input and failed runs. The message is a single line
// that names where (file, JSON path, body, stage, time) and what went wrong;
// the CLI prints it and maps the kind to the exit code (2 input, 1 run).
#include <stdexcept>
#include <string>

namespace gacompare {

enum class ErrorKind { input, run };

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

// Bad input: a scene file, a flag, a case file. Exit code 2.
inline Error input_error(const std::string& message) { return {ErrorKind::input, message}; }
// A run that failed (NaN in flight, a check that does not hold). Exit code 1.
inline Error run_error(const std::string& message) { return {ErrorKind::run, message}; }

}  // namespace gacompare
