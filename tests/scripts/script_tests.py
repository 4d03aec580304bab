"""The runner of the script tests: every function test_<name>(tmp) of a module, each in its own
temporary directory; prints PASS/FAIL per test and "N passed, M failed" last, and returns the
exit code (0 only when all pass)."""
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
