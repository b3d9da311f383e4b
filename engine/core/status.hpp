#pragma once
// Outcome of a numerical operation inside the time loop. Exceptions are used
// only at input boundaries (see input_error.hpp); everything after the scene
// has been accepted reports through a Status.
#include <string>
#include <string_view>
#include <utility>

namespace railvsi {

// kUnstable: the run monitor saw growth, chatter or an energy blow-up; the
// numbers are not a result even if every step converged.
enum class StatusCode { kOk, kDiverged, kNoConvergence, kInvalidInput, kUnstable };

class Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  static Status Ok() { return {}; }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // The name used in summaries and the result store.
  std::string_view name() const {
    switch (code_) {
      case StatusCode::kOk: return "ok";
      case StatusCode::kDiverged: return "diverged";
      case StatusCode::kNoConvergence: return "no_convergence";
      case StatusCode::kInvalidInput: return "invalid_input";
      case StatusCode::kUnstable: return "unstable";
    }
    return "unknown";
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

}  // namespace railvsi
