"""Unit tests of the add-on's Blender-free module (runner), with plain python3.

    python3 blender/tests/test_runner.py

Runs fake `shatter` scripts (shell) that succeed, refuse, crash or print garbage, and
checks the messages the add-on would show. Ends with 'blender-runner: N passed, N failed'.
"""

import doctest
import os
import stat
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                "shatter_fracture"))
import runner  # noqa: E402
from runner import Request, ShatterError  # noqa: E402


def fake(dir_, body, name="shatter"):
    path = os.path.join(dir_, name)
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + body + "\n")
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path


class FindBinary(unittest.TestCase):
    def test_preference_file_folder_missing_and_not_executable(self):
        with tempfile.TemporaryDirectory() as d:
            exe = fake(d, "exit 0")
            self.assertEqual(runner.find_binary(exe), exe)
            self.assertEqual(runner.find_binary(d), exe)  # a folder holding `shatter`
            with self.assertRaisesRegex(ShatterError, "does not exist: .*nope"):
                runner.find_binary(os.path.join(d, "nope"))
            plain = os.path.join(d, "plain")
            open(plain, "w").close()
            with self.assertRaisesRegex(ShatterError, "not executable"):
                runner.find_binary(plain)

    def test_path_lookup_and_its_absence(self):
        with tempfile.TemporaryDirectory() as d:
            exe = fake(d, "exit 0")
            old = os.environ.get("PATH", "")
            try:
                os.environ["PATH"] = d
                self.assertEqual(runner.find_binary(""), exe)
                os.environ["PATH"] = os.path.join(d, "empty")
                with self.assertRaisesRegex(ShatterError, "not found on PATH.*Preferences"):
                    runner.find_binary("  ")
            finally:
                os.environ["PATH"] = old


class CommandLine(unittest.TestCase):
    def test_each_method_gets_only_its_flags(self):
        cl = runner.command_line
        self.assertEqual(
            cl("s", "in.glb", "out.glb", Request(method="voronoi", pieces=7, pattern="radial",
                                                 impact=(1.0, 2.0, -3.0), seed=4, bonds=True)),
            ["s", "fracture", "in.glb", "--method", "voronoi", "--pieces", "7", "--pattern",
             "radial", "--impact", "1,2,-3", "--seed", "4", "--out", "out.glb", "--json",
             "--json-bonds"])
        # The impact point applies to the radial pattern only.
        self.assertNotIn("--impact", cl("s", "i", "o", Request(pattern="uniform", impact=(0, 0, 0))))
        self.assertEqual(
            cl("s", "i", "o", Request(method="voronoi", seeds=[(0, 0, 0)]), "seeds.xyz")[3:7],
            ["--method", "voronoi", "--seeds-file", "seeds.xyz"])
        tetra = cl("s", "i", "o", Request(method="tetra", random_vertices=9, skip=1,
                                          center=True, placement="thesis"))
        self.assertEqual(tetra[3:13], ["--method", "tetra", "--random-vertices", "9", "--skip",
                                       "1", "--placement", "thesis", "--center", "--seed"])
        self.assertNotIn("--pieces", tetra)
        self.assertEqual(cl("s", "i", "o", Request(method="slice", pieces=3))[3:7],
                         ["--method", "slice", "--pieces", "3"])

    def test_bad_requests_are_refused_before_running(self):
        for req, needle in ((Request(method="grid"), "unknown method"),
                            (Request(pieces=0), "at least 1"),
                            (Request(method="slice", seeds=[(0, 0, 0)]), "voronoi method only"),
                            (Request(seeds=[]), "no seed points"),
                            (Request(seed=-1), "negative")):
            with self.assertRaisesRegex(ShatterError, needle):
                runner.command_line("s", "i", "o", req, "seeds.xyz")

    def test_points_file_round_trips_exactly(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "p.xyz")
            pts = [(0.1, -2.5e-7, 3.0), (1.0 / 3.0, 0.0, -0.0)]
            runner.write_points(path, pts)
            back = [tuple(float(c) for c in line.split())
                    for line in open(path) if not line.startswith("#")]
            self.assertEqual(back, pts)


class Run(unittest.TestCase):
    def run_fake(self, body, extra=()):
        with tempfile.TemporaryDirectory() as d:
            return runner.run([fake(d, body), *extra])

    def test_success_returns_the_report_and_warnings(self):
        ticks = []
        with tempfile.TemporaryDirectory() as d:
            exe = fake(d, 'sleep 0.3; echo "warning: mesh was inward, flipped" >&2; '
                          'echo \'{"fragments": 3, "bonds": 2, "millis": 1.5}\'')
            res = runner.run([exe], progress=ticks.append, poll_seconds=0.05)
        self.assertEqual(res.report["fragments"], 3)
        self.assertEqual(res.warnings, ["mesh was inward, flipped"])
        self.assertTrue(ticks and all(b >= a for a, b in zip(ticks, ticks[1:])))

    def test_refusal_shows_shatters_message(self):
        with self.assertRaisesRegex(ShatterError,
                                    r"^shatter refused the input: in.glb: 42 boundary edges$"):
            self.run_fake('echo "error: in.glb: 42 boundary edges" >&2; exit 2')

    def test_internal_failure_crash_and_garbage(self):
        with self.assertRaisesRegex(ShatterError, r"exit code 1\): internal error"):
            self.run_fake('echo "error: internal error (a bug)" >&2; exit 1')
        with self.assertRaisesRegex(ShatterError, "killed by signal 9"):
            self.run_fake("kill -9 $$")
        with self.assertRaisesRegex(ShatterError, "not its JSON report"):
            self.run_fake("echo hello")
        with self.assertRaisesRegex(ShatterError, "no fragment count"):
            self.run_fake("echo '[1, 2]'")
        with self.assertRaisesRegex(ShatterError, "no bond list"):
            self.run_fake("echo '{\"fragments\": 1}'", extra=["--json-bonds"])

    def test_a_binary_that_cannot_start(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "shatter")
            with open(path, "w") as f:
                f.write("not a script")
            os.chmod(path, 0o755)
            with self.assertRaisesRegex(ShatterError, "Cannot start shatter"):
                runner.run([path])


def main():
    suite = unittest.TestSuite()
    suite.addTests(unittest.defaultTestLoader.loadTestsFromModule(sys.modules[__name__]))
    suite.addTests(doctest.DocTestSuite(runner))
    result = unittest.TextTestRunner(verbosity=1).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("blender-runner: %d passed, %d failed" % (result.testsRun - failed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
