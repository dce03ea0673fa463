#!/usr/bin/env python3
"""What may depend on what (docs/architecture.md#layering), checked on the
sources: every quoted #include of a module must resolve to a header of the
module itself or of a module it may use, no library module includes CLI11,
and lib/'s CMake targets may link nothing but Eigen and each other.

usage: check_layering.py <source root>
Prints one line per violation and exits 1 if there is any.
"""
import pathlib
import re
import sys

# Module -> the folders its headers are found in (the include paths).
INCLUDE_DIRS = {
    "lib": ["lib/include", "lib/src"],
    "port": ["port/include", "port/loopback/include", "port/posix/include", "port/cortex-m/include"],
    "hil": ["hil/codegen/include", "hil/codegen/c/include", "hil/bridge/include", "hil/controller/include",
            "hil/sil/include", "hil/common"],
    "analysis": ["analysis/include"],
    "mbd": ["mbd/include"],
    "fmu": ["fmu/include"],
    "validation": ["validation/include"],
    "cosim": ["cosim/include"],
    "tools": ["tools/cvtplant"],
    # The template controller project: a downstream user of the installed package.
    "examples": ["examples/controller-c"],
}
# Module -> the modules it may include (besides itself). A module's own tests
# (<module>/tests) are held to the module's rules; tests/ and bench/ may use
# everything and are not checked.
ALLOWED = {
    "lib": [],
    "port": ["lib"],
    "hil": ["lib", "port"],
    "analysis": ["lib"],
    "mbd": ["lib"],
    "fmu": ["lib"],
    "validation": ["lib", "analysis", "mbd"],
    # The reference behind the bridge and the closed-loop comparison: the
    # bus (hil/, port/), the reference (mbd/) and the scene mapping
    # (validation/). Host only; hil/ never includes it.
    "cosim": ["lib", "port", "hil", "mbd", "validation"],
    "tools": ["lib", "port", "hil", "analysis", "mbd", "validation", "fmu", "cosim"],
    "examples": ["lib", "port", "hil"],
}
# What a module's own tests may include besides: hil's tests run the
# template controller's law on the loopback bus.
TESTS_ALLOWED = {"hil": ["examples"]}
SOURCE_DIRS = {
    "lib": ["lib"],
    "port": ["port"],
    "hil": ["hil"],
    "analysis": ["analysis/include", "analysis/src"],
    "mbd": ["mbd/include", "mbd/src"],
    "fmu": ["fmu/include", "fmu/src"],
    "validation": ["validation/include", "validation/src"],
    "cosim": ["cosim/include", "cosim/src"],
    "tools": ["tools/cvtplant"],
    "examples": ["examples"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# The command-line parser belongs to the programs (tools/, hil/'s): a library
# module that included it could only be driven through a subprocess.
NO_CLI = ("lib", "port", "analysis", "mbd", "validation", "fmu", "cosim")
CLI_INCLUDE = re.compile(r'^\s*#\s*include\s+<CLI/', re.M)


def owner(root, header):
    """The module whose include folders hold `header`, or None."""
    for module, dirs in INCLUDE_DIRS.items():
        for d in dirs:
            if (root / d / header).is_file():
                return module
    return None


def check_sources(root):
    bad = []
    for module, dirs in SOURCE_DIRS.items():
        tests = f"{module}/tests"
        if not any(tests == d or tests.startswith(d + "/") for d in dirs):
            dirs = dirs + [tests]
        for d in dirs:
            base = root / d
            if not base.is_dir():
                continue
            for f in sorted(base.rglob("*")):
                if f.suffix not in (".hpp", ".cpp", ".h") or not f.is_file():
                    continue
                text = f.read_text(errors="replace")
                if module in NO_CLI and CLI_INCLUDE.search(text):
                    bad.append(f"{f.relative_to(root)}: {module}/ must not include CLI11 (the command line's parser)")
                for inc in INCLUDE.findall(text):
                    if (f.parent / inc).is_file():
                        continue  # a file beside the source: its own module
                    in_tests = str(f.relative_to(root)).startswith(tests + "/")
                    if in_tests and any((root / d / inc).is_file() for d in SOURCE_DIRS[module]):
                        continue  # a module's tests may test its private headers
                    dep = owner(root, inc)
                    if dep is None:
                        bad.append(f"{f.relative_to(root)}: \"{inc}\" is in no module's include folders")
                    elif dep != module and dep not in ALLOWED[module] and not (
                            in_tests and dep in TESTS_ALLOWED.get(module, [])):
                        bad.append(f"{f.relative_to(root)}: {module}/ must not include {dep}/ (\"{inc}\")")
    return bad


def check_lib_cmake(root):
    """lib/'s targets link only Eigen and lib's own targets."""
    text = (root / "lib/CMakeLists.txt").read_text()
    bad = []
    for m in re.finditer(r"target_link_libraries\(\s*(\S+)([^)]*)\)", text, re.S):
        for item in m.group(2).split():
            if item in ("PUBLIC", "PRIVATE", "INTERFACE") or item.startswith("cvtplant_") or item == "Eigen3::Eigen":
                continue
            bad.append(f"lib/CMakeLists.txt: {m.group(1)} links {item}; lib/ depends on Eigen alone")
    return bad


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    bad = check_sources(root) + check_lib_cmake(root)
    for b in bad:
        print(b)
    print(f"layering: {0 if bad else 1} passed, {1 if bad else 0} failed ({len(bad)} violations)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
