#include "flexgait/rimless/outcome.hpp"

#include <ostream>
#include <stdexcept>

#include "flexgait/numerics/hybrid_simulation.hpp"

namespace flexgait::rimless {

std::string_view failure_sentence(FailureReason reason) {
  for (const FailureEntry& e : kFailureTable)
    if (e.reason == reason) return e.sentence;
  throw std::logic_error("FailureReason without a sentence");
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
  const std::string_view sentence = failure_sentence(reason);
  std::string body;
  if (const auto at = sentence.find("{}"); at != std::string_view::npos) {
    body.append(sentence.substr(0, at)).append(detail).append(sentence.substr(at + 2));
  } else {
    body = sentence;
    if (!detail.empty()) body.append(" (").append(detail).append(")");
  }
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
