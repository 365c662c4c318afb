# Shared by the tests that run `cellctl emulate` in the background and talk to it over its
# pseudo-terminals. Sourced; the caller defines `cellctl`, `work`, `emulate_log`, `emulate_pid` and
# `fail`.

# publish_config SOURCE OUT: SOURCE with `publish_as: $work/<device>` right after the port: key of
# scu, spindle and encoder, and the encoder emulator's state_file in $work. Top-level keys start in
# column 0, so the current section is the last one seen.
publish_config() {
  awk -v dir="$work" '
    /^[A-Za-z_]+:/ { section = $1; sub(":", "", section) }
    { print }
    /^  port:/ && (section == "scu" || section == "spindle" || section == "encoder") {
      print "  publish_as: " dir "/" section
    }
  ' "$1" | sed -E "s|^(    state_file:).*|\1 $work/encoder.eeprom|" >"$2"
  [[ $(grep -c "^  publish_as: $work/" "$2") -eq 3 ]] ||
    fail "could not point publish_as of scu, spindle and encoder into $work (does $1 still have their port: keys?)"
  grep -q "^    state_file: $work/encoder.eeprom" "$2" ||
    fail "could not move the encoder emulator's state_file into $work"
}

# start_emulate CONFIG [OPTION…]: `cellctl -c CONFIG OPTION… emulate` in the background; waits (a
# condition, at most 10 s) until its three links are published and its loop runs.
start_emulate() {
  local config=$1
  shift
  "$cellctl" -c "$config" "$@" emulate >"$emulate_log" 2>&1 &
  emulate_pid=$!
  local _
  for _ in $(seq 100); do
    kill -0 "$emulate_pid" 2>/dev/null || fail "cellctl emulate exited before publishing its pseudo-terminals"
    if [[ -L $work/scu && -L $work/spindle && -L $work/encoder ]] &&
      grep -q "Ctrl-C ends the emulation" "$emulate_log"; then
      return 0
    fi
    sleep 0.1
  done
  fail "cellctl emulate did not publish $work/scu, $work/spindle and $work/encoder within 10 s"
}
