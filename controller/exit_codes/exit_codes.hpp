#pragma once
// What cellctl's exit status means, so scripts and operators can act on it. Its own part, below
// everything that ends a command or a job with one: the CLI, the job scheduler, and the plant link and
// page, whose answers give the status a run of the same command would have ended with.

namespace cellctl {

inline constexpr int kExitOk = 0;      // done as asked
inline constexpr int kExitFailed = 1;  // the command ran but did not succeed (device refused, fault)
inline constexpr int kExitUsage = 2;   // bad command line
inline constexpr int kExitConfig = 3;  // bad config or recipe (file:line:column on stderr)
inline constexpr int kExitLink = 4;    // a port could not be opened, or a device stopped answering
// The run ended and at least one device's safe state is unknown: its stop was never confirmed and no
// protection of its own bounds it (a spindle converter that stopped answering may still be turning).
// Takes precedence over 1 and 130: someone must look at the cell.
inline constexpr int kExitSafeStateUnknown = 5;
inline constexpr int kExitInterrupted = 130;  // ended by the operator: Ctrl-C, SIGTERM, a typed stop/abort

}  // namespace cellctl
