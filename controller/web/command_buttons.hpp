#pragma once
// Which of the page's command buttons the cell takes now, and why not the others: PackML's table
// (supervisor/packml.hpp, the one the arbiter judges every command by) read for the state the page
// shows, so a button is disabled exactly when its command would be refused, with the same words.
// Start, Home and Teach-In start jobs: only a standing controller (`cellctl serve`) takes them.

#include <optional>
#include <string_view>
#include <vector>

#include "schema/page_payloads.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::web {

// The PackML state named so (as the run's events name it), nullopt for any other text.
[[nodiscard]] std::optional<supervisor::State> state_named(std::string_view name) noexcept;

// Hold, unhold, stop, abort, reset, clear, start, home and teach-in, each enabled or with why not
// (the board's "buttons": schema/page_payloads.hpp). `starts_jobs`: this cellctl starts jobs (serve);
// an unknown state disables every button but Stop and Abort.
[[nodiscard]] std::vector<schema::CommandButton> command_buttons(std::string_view state, bool starts_jobs);

}  // namespace cellctl::web
