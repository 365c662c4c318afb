#pragma once
// The runs folder as the page's run history (GET /runs): each run record (a folder with a
// journal.jsonl), newest first, with its recipe, how it ended, how long it took, the safe state each
// device was left in, and whether its plot is there; its report is made on request (GET
// /runs/<run>/report, `cellctl report`'s text). Read on a server thread when the page asks, never on the
// loop. A record is read only at its two ends (the header line, the summary line), each bounded; what
// they say, and the history's JSON, is the schema's (schema/run_history.hpp).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "schema/run_history.hpp"

namespace cellctl::web {

inline constexpr std::size_t kMaxListedRuns = 50;
// A header or summary line longer than this is not read (a summary with many steps is a few KiB).
inline constexpr std::size_t kMaxRecordLine = 256 * 1024;

// A run's folder name as the page may ask for it: letters, digits, '-', '_', '.', not starting with a
// dot, at most 128 characters; never a path.
[[nodiscard]] bool plain_run_name(std::string_view name) noexcept;

// The history, empty when `folder` is empty (a `cellctl run` page has no runs folder of its own).
[[nodiscard]] schema::RunHistory run_history(const std::filesystem::path& folder);

// `cellctl report`'s text of run `name`, nullopt when there is no such record.
[[nodiscard]] std::optional<std::string> run_report(const std::filesystem::path& folder,
                                                    std::string_view name);

}  // namespace cellctl::web
