#!/usr/bin/python3
"""ctest hil.sil_tutorial (docs/sil.md#tests): every command block of
docs/tutorial.md, in page order, so that the page cannot rot.

  check_tutorial.py SOURCE_DIR BUILD_DIR WORK_DIR

- HOME is WORK_DIR/home (a fresh scratch directory), PATH starts with the
  tutorial's install prefix $HOME/cvtplant/bin, as the page's `export` says.
- The project's own configure and build lines of step 1 are the one thing not
  run: the test runs inside that build. They must still read as the page has
  them; `build/host-release` in the install line becomes BUILD_DIR.
- Blocks that use cvtplant-vcan-run or a real interface (can0) run in ONE
  micro-VM (hil/vcan-run, booted once): inside it vcan0 exists, so the page's
  own cvtplant-vcan-run calls run their command at once, and can0 becomes
  vcan0 (`--iface can0` becomes `--iface vcan0`) with the template standing
  in for the board. Host blocks before the
  first of them run before the VM, the ones after it afterwards (they only
  read what the VM runs wrote).
- Then the outcomes the page promises are checked: the two scenarios pass
  with the controller's bus criteria among them, the report is written, the
  undersized law fails no_gross_slip and only that, the real-time and can0
  runs are paced and fail nothing.
Exit 0 when the page held, 1 otherwise.
"""

import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

PROJECT_BUILD = ["cmake --preset host-release", "cmake --build --preset host-release"]


def blocks(page):
    text = open(page).read()
    return [m.group(1) for m in re.finditer(r"^```sh\n(.*?)^```$", text, re.S | re.M)]


def needs_vcan(b):
    return "cvtplant-vcan-run" in b or "--iface can0" in b


def suites(junit):
    return {s.get("name"): s for s in ET.parse(junit).getroot().iter("testsuite")}


def cases(suite):
    out = {}
    for c in suite.iter("testcase"):
        v = "fail" if c.find("failure") is not None else "skip" if c.find("skipped") is not None else "ok"
        out[c.get("name")] = (v, c.findtext("system-out"))
    return out


def main():
    src, build, work = (os.path.abspath(a) for a in sys.argv[1:4])
    home = os.path.join(work, "home")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(home)
    env = dict(os.environ, HOME=home, PATH=os.path.join(home, "cvtplant", "bin") + ":" + os.environ["PATH"])
    # The template is built as a user would, also inside the VM (step 5),
    # where a compiler cache on the read-only host root could not write.
    for k in ("CMAKE_C_COMPILER_LAUNCHER", "CMAKE_CXX_COMPILER_LAUNCHER"):
        env.pop(k, None)
    fails = []
    bs = blocks(os.path.join(src, "docs", "tutorial.md"))
    first = bs[0].splitlines()
    for line in PROJECT_BUILD:
        if line not in first:
            fails.append("step 1 no longer has '%s'" % line)
    bs[0] = "\n".join(l for l in first if l not in PROJECT_BUILD).replace("build/host-release", build) + "\n"
    vm_at = [i for i, b in enumerate(bs) if needs_vcan(b)]
    before = [b for i, b in enumerate(bs) if not needs_vcan(b) and i < vm_at[0]]
    after = [b for i, b in enumerate(bs) if not needs_vcan(b) and i > vm_at[0]]
    vm = []
    for i in vm_at:
        b = bs[i]
        if "--iface can0" in b:
            # The board of step 7: the template on vcan0, in real time.
            b = ('"$HOME/my-controller/build/cvt-controller" --iface vcan0 --mode realtime '
                 '> "$HOME/board.log" 2>&1 &\nboard=$!\n' + re.sub(r"--iface can0\b", "--iface vcan0", b) +
                 'rc=$?\nkill $board; wait $board\n(exit $rc)\n')
        vm.append(b)

    def run(script, where):
        r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", script], cwd=src, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print(r.stdout, end="")
        if r.returncode != 0:
            fails.append("%s: exit %d:\n%s" % (where, r.returncode, script))
        return r.returncode == 0

    ok = all(run(b, "host block %d" % (k + 1)) for k, b in enumerate(before))
    if ok:
        # One VM for every vcan block; each block in a subshell, stopping at
        # the first that fails.
        script = "set -e\n" + "".join(
            "t0=$(date +%%s.%%N)\n(\n%s)\necho \"hil.sil_tutorial: vcan block %d done in $(awk \"BEGIN{printf \\\"%%.1f\\\", $(date +%%s.%%N) - $t0}\") s\"\n"
            % (b, k + 1) for k, b in enumerate(vm))
        path = os.path.join(home, "vcan-blocks.sh")
        open(path, "w").write(script)
        ok = run('"%s/hil/vcan-run" --rw "%s" -- bash "%s"' % (src, home, path), "the vcan blocks")
    if ok:
        for k, b in enumerate(after):
            run(b, "host block after the VM %d" % (k + 1))

    # What the page says happens.
    ctl = os.path.join(home, "my-controller")
    try:
        s = suites(os.path.join(ctl, "sil-out", "sil-junit.xml"))
        for n in ("sil.ratio-sweep", "sil.kick-down"):
            c = cases(s[n])
            # Cut at 5 s: the end stops (12-20 s) are not judged.
            bad = [k for k, (v, _) in c.items() if v != "ok" and not (v == "skip" and k == "end_stops_reached")]
            need = ["controller_answered", "commands_on_time", "commands_e2e_valid", "commands_in_range",
                    "ratio_tracked", "no_gross_slip", "slip_bounded"]
            if bad or not all(k in c for k in need):
                fails.append("%s: not every criterion passed, or one missing: %s" % (n, bad))
            print("hil.sil_tutorial: %s: %d criteria passed; %s" % (n, len(c), c["ratio_tracked"][1]))
        u = cases(suites(os.path.join(ctl, "sil-undersized", "sil-junit.xml"))["sil.kick-down"])
        failed = [k for k, (v, _) in u.items() if v == "fail"]
        if failed != ["no_gross_slip"]:
            fails.append("the undersized law: failed %s, expected exactly no_gross_slip" % failed)
        print("hil.sil_tutorial: undersized law: FAIL no_gross_slip: %s" % u["no_gross_slip"][1])
        for run_dir in ("sil-realtime", "sil-can0"):
            r = cases(suites(os.path.join(ctl, run_dir, "sil-junit.xml"))["sil.kick-down.realtime"])
            bad = [k for k, (v, _) in r.items() if v == "fail"]
            if bad or r["realtime_paced"][0] != "ok" or "controller_on_time" not in r:
                fails.append("%s: failed %s" % (run_dir, bad))
            print("hil.sil_tutorial: %s: realtime_paced: %s; controller_on_time: %s %s" % (
                run_dir, r["realtime_paced"][1], r["controller_on_time"][0], r["controller_on_time"][1]))
    except (OSError, KeyError, ET.ParseError) as e:
        fails.append("a report the page promises is missing: %r" % e)
    html = os.path.join(ctl, "sil-out", "sil-report.html")
    if not os.path.isfile(html) or "kick-down" not in open(html).read():
        fails.append("no HTML report with the scenarios at %s" % html)
    for f in fails:
        print("hil.sil_tutorial: FAIL: %s" % f)
    print("hil.sil_tutorial: %s" % ("PASSED" if not fails else "FAILED"))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
