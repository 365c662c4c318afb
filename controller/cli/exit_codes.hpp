#pragma once
// What cellctl's exit status means, so scripts and operators can act on it.

namespace cellctl::cli {

inline constexpr int kExitOk = 0;             // done as asked
inline constexpr int kExitFailed = 1;         // the command ran but did not succeed (device refused, fault)
inline constexpr int kExitUsage = 2;          // bad command line
inline constexpr int kExitConfig = 3;         // bad config or recipe (file:line:column on stderr)
inline constexpr int kExitLink = 4;           // a port could not be opened, or a device stopped answering
inline constexpr int kExitInterrupted = 130;  // ended by the operator: Ctrl-C, SIGTERM, a typed stop/abort

}  // namespace cellctl::cli
