#!/usr/bin/python3
"""cellctl installed like a service: the Debian package CPack builds from this build tree, unpacked into a
scratch root, and `cmake --install` with a DESTDIR.

usage: package_test.py BUILD_DIR SOURCE_DIR OUT_DIR

Checks: cpack makes cellctl_<version>_<arch>.deb; its control file depends on systemd, and its
maintainer scripts (postinst: the user and /etc/cellctl; prerm) are there and parse (sh -n); unpacked
(dpkg-deb -x) into OUT_DIR/root it holds the binary, the unit, the sysusers file, the example configs
(the default cell, config/examples/, the recipes) and the README; systemd-sysusers --root makes from
it the system user cellctl (home /var/lib/cellctl, no shell, in dialout) in the scratch root; the unit runs `cellctl serve` as the
user cellctl (never root) with LimitRTPRIO, LimitMEMLOCK and CPUAffinity, no capability, and a restart
policy that leaves exits 2, 3, 5 and crashes to a person; `systemd-analyze verify` accepts the unit
with nothing to say (it warns and still exits 0 on an unknown key or a bad value, so any output fails
the test) — verified on a copy whose ExecStart names the unpacked binary (OUT_DIR/root/usr/bin/cellctl),
since systemd-analyze looks for the binary on this machine and its --root finds no systemd there; the
unpacked binary, given the unit's own command line with /etc/cellctl and /var/lib/cellctl moved under
OUT_DIR, stands by and ends with 0 on SIGTERM, and runs the packaged demo recipe in virtual time to
Complete; `cmake --install --prefix /usr` with a DESTDIR installs the same files, its unit naming
/usr/bin/cellctl (not the DESTDIR). Prints the package's size and the time cpack took.
"""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

build, source, out = sys.argv[1:4]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
root = os.path.join(out, "root")
UNIT = "usr/lib/systemd/system/cellctl.service"


def fail(message):
    print(f"FAIL: {message}\n(output kept in {out})")
    sys.exit(1)


def run(argv, **kwargs):
    r = subprocess.run(argv, capture_output=True, text=True, **kwargs)
    if r.returncode != 0:
        fail(f"{' '.join(argv)} ended with {r.returncode}:\n{r.stdout}{r.stderr}")
    return r


def files_under(top):
    return sorted(os.path.relpath(os.path.join(d, f), top) for d, _, fs in os.walk(top) for f in fs)


# --- the package -------------------------------------------------------------------------------------
# A sanitized tree (the suite's asan) is never what one packages, and dpkg-shlibdeps takes 26 s on its
# 100 MB binary: there the library dependencies are left out (-D …SHLIBDEPS=OFF), everywhere else
# they are checked.
sanitized = "-fsanitize" in open(os.path.join(build, "CMakeCache.txt")).read()
started = time.monotonic()
run(["cpack", "--config", os.path.join(build, "CPackConfig.cmake"), "-B", os.path.join(out, "package")] +
    (["-D", "CPACK_DEBIAN_PACKAGE_SHLIBDEPS=OFF"] if sanitized else []))
cpack_s = time.monotonic() - started
debs = [f for f in os.listdir(os.path.join(out, "package")) if f.endswith(".deb")]
if len(debs) != 1 or not re.fullmatch(r"cellctl_[0-9.]+_[a-z0-9]+\.deb", debs[0]):
    fail(f"cpack made {debs}, expected one cellctl_<version>_<arch>.deb")
deb = os.path.join(out, "package", debs[0])

control = os.path.join(out, "control")
run(["dpkg-deb", "-e", deb, control])
fields = run(["dpkg-deb", "-f", deb, "Package", "Depends"]).stdout
if "Package: cellctl" not in fields or not re.search(r"Depends:.*\bsystemd\b", fields):
    fail(f"the control file does not name cellctl or depend on systemd:\n{fields}")
if not sanitized and not re.search(r"Depends:.*\blibmosquitto1\b.*\blibstdc\+\+6\b", fields):
    fail(f"the control file does not depend on the libraries cellctl links (dpkg-shlibdeps):\n{fields}")
for script in ("postinst", "prerm"):
    path = os.path.join(control, script)
    if not os.access(path, os.X_OK):
        fail(f"the package has no executable {script}")
    run(["sh", "-n", path])
if "systemd-sysusers cellctl.conf" not in open(os.path.join(control, "postinst")).read():
    fail("the postinst does not make the user cellctl")

run(["dpkg-deb", "-x", deb, root])
packaged = files_under(root)
for f in ["usr/bin/cellctl", UNIT, "usr/lib/sysusers.d/cellctl.conf", "usr/share/doc/cellctl/README.md",
          "usr/share/cellctl/examples/cell.yaml", "usr/share/cellctl/examples/cell-hardware.yaml",
          "usr/share/cellctl/examples/plant-link.yaml", "usr/share/cellctl/examples/prometheus.yml",
          "usr/share/cellctl/examples/grafana-cellctl.json", "usr/share/cellctl/examples/mosquitto/mosquitto.conf",
          "usr/share/cellctl/examples/mosquitto/cellctl.acl", "usr/share/cellctl/examples/recipes/demo.yaml"]:
    if f not in packaged:
        fail(f"the package has no {f}; it has:\n" + "\n".join(packaged))
# What the postinst's systemd-sysusers makes, in the scratch root (given a base system's root and dialout).
os.makedirs(os.path.join(root, "etc"))
with open(os.path.join(root, "etc/passwd"), "w") as f:
    f.write("root:x:0:0:root:/root:/bin/bash\n")
with open(os.path.join(root, "etc/group"), "w") as f:
    f.write("root:x:0:\ndialout:x:20:\n")
run(["systemd-sysusers", f"--root={root}", os.path.join(root, "usr/lib/sysusers.d/cellctl.conf")])
passwd, group = open(os.path.join(root, "etc/passwd")).read(), open(os.path.join(root, "etc/group")).read()
if not re.search(r"^cellctl:x:[1-9][0-9]*:[0-9]+:[^:]*:/var/lib/cellctl:/usr/sbin/nologin$", passwd, re.M) or \
        not re.search(r"^dialout:x:20:cellctl$", group, re.M):
    fail(f"systemd-sysusers did not make the system user cellctl in dialout:\n{passwd}{group}")

# --- the unit ------------------------------------------------------------------------------------------
unit_text = open(os.path.join(root, UNIT)).read()
unit = {}
for line in unit_text.splitlines():
    if "=" in line and not line.startswith(("#", "[")):
        key, value = line.split("=", 1)
        unit.setdefault(key.strip(), []).append(value.strip())


def one(key):
    values = unit.get(key, [])
    if len(values) != 1:
        fail(f"the unit sets {key} {len(values)} times, expected once: {values}")
    return values[0]


exec_start = one("ExecStart").split()
if exec_start[0] != "/usr/bin/cellctl" or "serve" not in exec_start:
    fail(f"ExecStart does not run the packaged /usr/bin/cellctl serve: {exec_start}")
if one("User") != "cellctl":
    fail(f"the unit runs as {one('User')}, expected the user cellctl")
if one("LimitRTPRIO") != "80" or one("LimitMEMLOCK") != "infinity" or not one("CPUAffinity"):
    fail("the unit lacks LimitRTPRIO=80 (the config's default loop.priority), LimitMEMLOCK=infinity or CPUAffinity")
if one("CapabilityBoundingSet") != "" or one("AmbientCapabilities") != "":
    fail("the unit keeps capabilities; the limits are all the real-time set-up needs")
prevent = one("RestartPreventExitStatus").split()
if one("Restart") != "on-failure" or not {"2", "3", "5", "SIGSEGV", "SIGABRT", "SIGKILL"} <= set(prevent):
    fail(f"the restart policy restarts what a person must look at first: Restart={one('Restart')}, "
         f"RestartPreventExitStatus={prevent}")

verify_dir = os.path.join(out, "verify")
os.makedirs(verify_dir)
unpacked_binary = os.path.join(root, "usr/bin/cellctl")
with open(os.path.join(verify_dir, "cellctl.service"), "w") as f:
    f.write(unit_text.replace("ExecStart=/usr/bin/cellctl ", f"ExecStart={unpacked_binary} "))
verify = subprocess.run(["systemd-analyze", "verify", "--man=no", os.path.join(verify_dir, "cellctl.service")],
                        capture_output=True, text=True)
if verify.returncode != 0 or verify.stdout.strip() or verify.stderr.strip():
    fail(f"systemd-analyze verify (exit {verify.returncode}) says:\n{verify.stdout}{verify.stderr}")

# --- the packaged binary, as the unit starts it ----------------------------------------------------------
scratch = os.path.join(out, "cell")
cell_dir, state_dir = os.path.join(scratch, "etc/cellctl"), os.path.join(scratch, "var/lib/cellctl")
os.makedirs(os.path.join(cell_dir, "recipes"))
os.makedirs(state_dir)
examples = os.path.join(root, "usr/share/cellctl/examples")
config = open(os.path.join(examples, "cell.yaml")).read()
config, moved = re.subn(r"\n    state_file: [^\n]*", f"\n    state_file: {state_dir}/encoder.eeprom", config)
if moved != 1:
    fail("the packaged cell.yaml has no encoder state_file to move")
with open(os.path.join(cell_dir, "cell.yaml"), "w") as f:
    f.write(config)
shutil.copy(os.path.join(examples, "recipes/demo.yaml"), os.path.join(cell_dir, "recipes"))
with open(os.path.join(scratch, "token"), "w") as f:
    f.write("package-test-token-0123456789\n")
with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
argv = [unpacked_binary] + [w.replace("/etc/cellctl", cell_dir).replace("/var/lib/cellctl", state_dir)
                            for w in exec_start[1:] if w != "$CELLCTL_SERVE_OPTIONS"]
argv += ["--virtual-time", "--http", f"127.0.0.1:{port}", "--http-token-file", os.path.join(scratch, "token")]
log_path = os.path.join(out, "serve.log")
with open(log_path, "w") as log:
    serve = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)
deadline = time.monotonic() + 60
while "standing by" not in open(log_path).read():
    if serve.poll() is not None or time.monotonic() > deadline:
        serve.kill()
        fail(f"the unit's command line did not stand by ({' '.join(argv)}):\n{open(log_path).read()}")
    time.sleep(0.05)
serve.send_signal(signal.SIGTERM)
try:
    if serve.wait(timeout=30) != 0:
        fail(f"serve ended with {serve.returncode} after SIGTERM, expected 0:\n{open(log_path).read()}")
except subprocess.TimeoutExpired:
    serve.kill()
    fail("serve did not end after SIGTERM")
demo = run([unpacked_binary, "-c", os.path.join(cell_dir, "cell.yaml"), "run", os.path.join(cell_dir, "recipes/demo.yaml"),
            "--virtual-time", "--journal", os.path.join(state_dir, "runs/demo")])
if "outcome: complete" not in demo.stdout:
    fail(f"the packaged binary did not run the packaged demo to Complete:\n{demo.stdout}")

# --- cmake --install with a DESTDIR ------------------------------------------------------------------------
destdir = os.path.join(out, "destdir")
run(["cmake", "--install", build, "--prefix", "/usr"], env=dict(os.environ, DESTDIR=destdir))
installed = files_under(destdir)
if installed != packaged:
    fail(f"cmake --install and the package differ: only installed {sorted(set(installed) - set(packaged))}, "
         f"only packaged {sorted(set(packaged) - set(installed))}")
if f"ExecStart=/usr/bin/cellctl " not in open(os.path.join(destdir, UNIT)).read():
    fail("the unit cmake --install wrote does not name /usr/bin/cellctl")

size = os.path.getsize(deb)
print(f"package: {debs[0]}, {size / 1e6:.1f} MB ({len(packaged)} files), built by cpack in {cpack_s:.1f} s"
      f"{' (sanitized: without its library dependencies)' if sanitized else ''}; "
      f"systemd-analyze verify: clean; the unit's command line stands by and ends with 0; demo Complete — passed")
