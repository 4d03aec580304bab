"""The runner of the script tests: every function test_<name>(tmp) of a module, each in its own
temporary directory; prints PASS/FAIL per test and "N passed, M failed" last, and returns the
exit code (0 only when all pass)."""
import argparse
import os
import tempfile
import traceback


def run(namespace):
    tests = [(name, fn) for name, fn in namespace.items() if name.startswith("test_")]
    passed = failed = 0
    for name, fn in tests:
        with tempfile.TemporaryDirectory(prefix="granjet_script_test_") as tmp:
            try:
                fn(tmp)
                passed += 1
                print(f"PASS {name}")
            except Exception:  # noqa: BLE001 - report every failure and go on
                failed += 1
                print(f"FAIL {name}\n{traceback.format_exc()}")
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


def main_with_granjet(namespace, root, cleanup):
    """The test scripts' main: --granjet PATH (default build/app/granjet under root) into the
    module's GRANJET, the tests run, then cleanup() whatever happened."""
    parser = argparse.ArgumentParser(description=namespace["__doc__"].split("\n")[0])
    parser.add_argument("--granjet", default=os.path.join(root, "build", "app", "granjet"))
    namespace["GRANJET"] = parser.parse_args().granjet
    try:
        return run(namespace)
    finally:
        cleanup()
