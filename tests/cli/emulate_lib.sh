# Shared by the tests that run `cellctl emulate` in the background and talk to it over its
# pseudo-terminals. Sourced; the caller defines `cellctl`, `work`, `emulate_log`, `emulate_pid` and
# `fail`.

# publish_config SOURCE OUT: SOURCE with `publish_as: $work/<device>` right after the port: key of
# scu, spindle and encoder, and the encoder emulator's state_file in $work. Top-level keys start in
# column 0, so the current section is the last one seen. These tests check what the commands do over
# real pseudo-terminals, not how soon a silent line is noticed: a pty's bytes wait for a kernel worker
# of normal priority, which on a 2-core machine kept busy (even by niced processes) was seen to hold
# them for over a second. So the SCU's and the spindle's sessions, and the monitor, allow 3 s of
# silence here (1 s and 0.3 s in the shipped cell; their limits are tested in virtual time).
publish_config() {
  awk -v dir="$work" '
    /^[A-Za-z_]+:/ { section = $1; sub(":", "", section) }
    { print }
    /^  port:/ && (section == "scu" || section == "spindle" || section == "encoder") {
      print "  publish_as: " dir "/" section
    }
  ' "$1" | sed -E -e "s|^(    state_file:).*|\1 $work/encoder.eeprom|" \
    -e "s|^(  link_fault_after_ms:) 1000\b|\1 3000|" -e "s|^(  link_silence_ms:) 300\b|\1 3000|" >"$2"
  [[ $(grep -c "^  publish_as: $work/" "$2") -eq 3 ]] ||
    fail "could not point publish_as of scu, spindle and encoder into $work (does $1 still have their port: keys?)"
  [[ $(grep -c -E "^  (link_fault_after_ms|link_silence_ms): 3000$" "$2") -eq 3 ]] ||
    fail "could not give the SCU, the spindle and the monitor 3 s of silence in $2"
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

# client_config EMULATED OUT: the cell of the commands that talk to `cellctl emulate` as to hardware —
# EMULATED (made by publish_config) with each device's port the pseudo-terminal published in $work,
# and the publish_as keys dropped. Call after publish_config (and after any edit of EMULATED that the
# client shares, such as its state_dir).
client_config() {
  awk -v dir="$work" '
    /^[A-Za-z_]+:/ { section = $1; sub(":", "", section) }
    /^  port: emulated/ && (section == "scu" || section == "spindle" || section == "encoder") {
      print "  port: " dir "/" section; next
    }
    { print }
  ' "$1" | grep -v "^  publish_as:" >"$2"
  [[ $(grep -c "^  port: $work/" "$2") -eq 3 ]] || fail "could not point the ports of $2 into $work"
}
