#pragma once
// The HTTP status of a command's answer (schema/command_answer.hpp; its body says the same in words,
// and the page shows the words whatever the status):
//   200 taken (or done);
//   409 Conflict: refused by the cell's state — PackML's interlocks, a job in progress or ending,
//       starts blocked after a job that left a device unknown, the run's own refusal;
//   410 Gone: not meant now — expired (older than max_command_age_ms, or an issue time too far
//       ahead), or its client had gone. Not 408: a client (a browser among them) may repeat a request
//       answered 408 by itself, and a repeated command would arrive fresh;
//   400 the payload is no JSON object within the limits; 404 no such command;
//   422 the command as given cannot be carried out: a recipe not valid for the cell (with "exit": 3
//       and its errors), a field missing or out of range, axes that cannot be homed;
//   504 the run gave no answer in time: the outcome is unknown (see the state).
// The arbiter says why in words only (command::Taken), so the kind is read from them, here alone;
// tests/web/answer_status_test.cpp holds the words of each source against it.

#include "schema/command_answer.hpp"

namespace cellctl::web {

[[nodiscard]] int answer_status(const schema::CommandAnswer& answer);

}  // namespace cellctl::web
