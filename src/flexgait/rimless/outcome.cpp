#include "flexgait/rimless/outcome.hpp"

#include <ostream>
#include <stdexcept>

#include "flexgait/numerics/hybrid_simulation.hpp"

namespace flexgait::rimless {

std::string_view failure_sentence(FailureReason reason) {
  return numerics::reason_sentence(kFailureTable, reason);
}

FailureReason loop_failure_reason(numerics::LoopFailure what) {
  switch (what) {
    case numerics::LoopFailure::Solver:
      return FailureReason::SolverFailure;
    case numerics::LoopFailure::RepeatedEvent:
      return FailureReason::RepeatedEvent;
    case numerics::LoopFailure::Zeno:
      return FailureReason::Zeno;
  }
  throw std::logic_error("LoopFailure without a reason");
}

std::string Failure::text() const {
  const std::string body = numerics::reason_text(kFailureTable, reason, detail);
  return stage.empty() ? body : stage + ": " + body;
}

Failure Failure::in_stage(std::string_view outer) const {
  Failure f = *this;
  f.stage = stage.empty() ? std::string(outer) : std::string(outer) + ": " + stage;
  return f;
}

std::string text_of(const std::optional<Failure>& failure) {
  return failure ? failure->text() : std::string();
}

std::ostream& operator<<(std::ostream& out, const Failure& failure) {
  return out << failure.text();
}

}  // namespace flexgait::rimless
