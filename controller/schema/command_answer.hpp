#pragma once
// The answer to a command, as the plant reads it on its `response` topic and the page as the reply to
// its POST: typed, and its JSON. plant_link::CommandDesk gives them; the link and the page send them.
//   {"command","id" (when given),"ok","outcome" or "reason","source" (when known),
//    "t" (when the run took it),"valid" (a start's recipe was valid),"exit","errors" (it was not)}

#include <optional>
#include <string>
#include <vector>

#include "schema/command_payload.hpp"

namespace cellctl::schema {

struct CommandAnswer {
  std::string command;
  AnswerId id;
  bool ok = false;
  std::string text;         // "outcome" when ok, "reason" when not
  std::string source;       // whose command it answers (command/command_source.hpp's words); none when empty
  std::optional<double> t;  // the run's time when the run answered it
  bool valid = false;       // a start whose recipe is valid for the cell
  // A start whose recipe is not: the exit status `cellctl check` would end with, and its problems,
  // file:line:col each.
  std::optional<int> exit;
  std::vector<std::string> errors;
};

[[nodiscard]] std::string answer_payload(const CommandAnswer& answer);

}  // namespace cellctl::schema
