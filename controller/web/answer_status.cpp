#include "web/answer_status.hpp"

#include <array>
#include <string>
#include <string_view>
#include <utility>

namespace cellctl::web {
namespace {

// Phrases of the refusals, first match wins; their sources: command/order.cpp (expired),
// web/hand_over.hpp (client gone), plant_link/command_desk.cpp (payload, answers from the run),
// command/arbiter.cpp and jobs/job_scheduler.cpp (the state).
constexpr std::array<std::pair<std::string_view, int>, 14> kPhrases{{
    {"expired:", 410},
    {"its age is unknown", 410},
    {"its client has gone", 410},
    {"(expected {", 400},
    {"is not a command", 404},
    {"gave no answer", 504},
    {"no answer from the run", 504},
    {"is not possible", 409},
    {"needs a job in progress", 409},
    {"refused", 409},
    {"no start is taken", 409},
    {"still in progress", 409},
    {"before it took the command", 409},
    {"drives one run", 409},  // `cellctl run`: the start is valid, but this process takes none
}};

}  // namespace

int answer_status(const schema::CommandAnswer& answer) {
  if (answer.ok) return 200;
  if (answer.exit) return 422;  // a recipe not valid for the cell
  for (const auto& [phrase, status] : kPhrases)
    if (answer.text.find(phrase) != std::string::npos) return status;
  return 422;
}

}  // namespace cellctl::web
