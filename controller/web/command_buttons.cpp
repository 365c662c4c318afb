#include "web/command_buttons.hpp"

#include <fmt/format.h>

#include <array>
#include <string>
#include <utility>

namespace cellctl::web {
namespace {

using supervisor::Command;
using supervisor::State;

constexpr std::array kStates{State::idle,      State::starting,  State::execute,    State::holding,
                             State::held,      State::unholding, State::stopping,   State::stopped,
                             State::aborting,  State::aborted,   State::completing, State::complete,
                             State::resetting, State::clearing};

}  // namespace

std::optional<State> state_named(std::string_view name) noexcept {
  for (const auto s : kStates)
    if (supervisor::to_string(s) == name) return s;
  return std::nullopt;
}

std::vector<schema::CommandButton> command_buttons(std::string_view state, bool starts_jobs) {
  std::vector<schema::CommandButton> out;
  const auto s = state_named(state);
  for (const auto c :
       {Command::hold, Command::unhold, Command::stop, Command::abort, Command::reset, Command::clear}) {
    const bool brings_to_rest = c == Command::stop || c == Command::abort;
    // Not knowing the state never keeps a stop from the operator.
    const std::string reason = s ? std::string(supervisor::refusal(*s, c))
                               : brings_to_rest
                                   ? std::string()
                                   : fmt::format("the cell's state ({}) is not known yet", state);
    out.push_back({std::string(supervisor::to_string(c)), reason});
  }
  const std::string start = !starts_jobs
                                ? "this cellctl drives one run (cellctl run): jobs start under cellctl serve"
                            : s ? std::string(supervisor::refusal(*s, Command::start))
                                : fmt::format("the cell's state ({}) is not known yet", state);
  for (const auto* job : {"start", "home", "teach-in"}) out.push_back({job, start});
  return out;
}

}  // namespace cellctl::web
