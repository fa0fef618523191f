"""The bhm Python module against the bhm command line: same simulation, same decoded champion,
same run directory, same validation problems; and simulate() releases the GIL.

Run by ctest as: python3 test_bhm_module.py BHM_EXECUTABLE SOURCE_DIR (PYTHONPATH=build/python).
"""
import copy
import csv
import json
import os
import pathlib
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import warnings

import numpy as np

import bhm

BHM = sys.argv[1]
SOURCE = sys.argv[2]
QUICK_DEMO = os.path.join(SOURCE, "assets", "experiments", "quick-demo.json")


def run_cli(*args):
    done = subprocess.run([BHM, *args], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def small_experiment():
    """quick-demo with a short evaluation and a tiny evolution, as a dict."""
    with open(QUICK_DEMO) as f:
        e = json.load(f)
    e["simulation"]["settle_s"] = 0.02
    e["simulation"]["evaluate_s"] = 0.08
    e["simulation"]["record_fps"] = 100
    e["evolution"]["population"] = 4
    e["evolution"]["generations"] = 2
    return e


# An 8 x 6 x 5 workspace; a 6 x 3 x 2 slab, muscle on top, held at x-.
BODY = {"size": [6, 3, 2], "layers": ["111111" * 3, "222222" * 3]}


class Fixture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name
        cls.experiment_path = os.path.join(cls.dir, "experiment.json")
        with open(cls.experiment_path, "w") as f:
            json.dump(small_experiment(), f)
        cls.body_path = os.path.join(cls.dir, "body.json")
        with open(cls.body_path, "w") as f:
            json.dump(BODY, f)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()


class Simulate(Fixture):
    def test_same_trajectory_and_summary_as_bhm_simulate(self):
        out = os.path.join(self.dir, "sim")
        status, text = run_cli("simulate", self.experiment_path, "--body", self.body_path,
                               "--out", out)
        self.assertEqual(status, 0, text)
        result = bhm.simulate(self.experiment_path, self.body_path)
        with open(os.path.join(out, "trajectory.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), len(result["t"]))
        t = np.array([float(r["t_s"]) for r in rows])
        com = np.array([[float(r["com_x_m"]), float(r["com_y_m"]), float(r["com_z_m"])]
                        for r in rows])
        tip = np.array([[float(r["tip_x_m"]), float(r["tip_y_m"]), float(r["tip_z_m"])]
                        for r in rows])
        # The engine is deterministic and the CSV round-trips doubles: equal to the bit.
        np.testing.assert_array_equal(result["t"], t)
        np.testing.assert_array_equal(result["com"], com)
        np.testing.assert_array_equal(result["tip"], tip)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        for key in ("voxels", "links", "steps", "dt_s", "displacement_3d_voxels",
                    "displacement_yz_voxels", "max_displacement_3d_voxels", "com_end_m",
                    "samples", "settle_s"):
            self.assertEqual(result["summary"][key], summary[key], key)
        frames, voxels = result["positions"].shape[:2]
        self.assertEqual(voxels, 36)
        self.assertEqual(frames, len(result["frame_t"]))
        self.assertEqual(result["positions"].dtype, np.float32)
        self.assertEqual(result["orientations"].shape, (frames, 36, 4))
        # The centre of mass is the mean voxel position (one material density here).
        np.testing.assert_allclose(result["positions"][-1].mean(axis=0), result["com"][-1],
                                   atol=1e-6)

    def test_dicts_and_seconds(self):
        result = bhm.simulate(small_experiment(), BODY, seconds=0.03)
        self.assertAlmostEqual(result["summary"]["sim_time_s"], 0.03, delta=1e-3)
        self.assertEqual(result["lattice"], (8, 6, 5))
        with self.assertRaises(ValueError) as caught:
            bhm.simulate(small_experiment(), {"size": [9, 9, 9], "layers": ["1" * 81] * 9})
        self.assertIn("size", str(caught.exception))

    def test_two_threads_simulate_concurrently(self):
        """While one thread simulates, another runs Python: the GIL is released."""
        e = small_experiment()
        e["simulation"]["evaluate_s"] = 1.0
        results = {}

        def work(name):
            start = time.perf_counter()
            results[name] = bhm.simulate(e, BODY)
            results[name + "_span"] = (start, time.perf_counter())

        solo_start = time.perf_counter()
        work("solo")
        solo = time.perf_counter() - solo_start
        threads = [threading.Thread(target=work, args=(n,)) for n in ("a", "b")]
        ticks = 0
        pair_start = time.perf_counter()
        for th in threads:
            th.start()
        while any(th.is_alive() for th in threads):
            ticks += 1  # runs only when no simulation holds the GIL
            time.sleep(0.001)
        pair = time.perf_counter() - pair_start
        a, b = results["a_span"], results["b_span"]
        self.assertLess(max(a[0], b[0]), min(a[1], b[1]), "the two simulations overlapped")
        # Holding the GIL, the main thread could only tick between the two calls (a few times).
        self.assertGreater(ticks, 20, "the main thread ran meanwhile")
        np.testing.assert_array_equal(results["a"]["com"], results["b"]["com"])
        print(f"\none simulation {solo:.2f} s, two in two threads {pair:.2f} s "
              f"({2 * solo / pair:.2f}x), main-thread ticks {ticks}", file=sys.stderr)


class Validate(Fixture):
    def test_same_problems_as_bhm_validate(self):
        bad = small_experiment()
        bad["materials"][0]["poisson_ratio"] = 0.7
        bad["workspace"]["voxel_size_m"] = -1
        path = os.path.join(self.dir, "bad.json")
        with open(path, "w") as f:
            json.dump(bad, f)
        problems = bhm.validate(path)
        self.assertGreaterEqual(len(problems), 2)
        status, text = run_cli("validate", path)
        self.assertEqual(status, 1)
        self.assertEqual(sorted(problems), sorted(text.strip().splitlines()))
        self.assertEqual(bhm.validate(self.experiment_path), [])
        self.assertEqual(bhm.validate(self.body_path, self.experiment_path), [])
        big = os.path.join(self.dir, "big.json")
        with open(big, "w") as f:
            json.dump({"size": [9, 1, 1], "layers": ["1" * 9]}, f)
        self.assertTrue(bhm.validate(big, self.experiment_path))
        self.assertTrue(bhm.validate(os.path.join(self.dir, "missing.json")))

    def test_library_warnings_are_python_warnings_as_the_command_line_prints_them(self):
        # Issue 41 R10: a damaged library file is named; the module said nothing.
        library = os.path.join(self.dir, "library")
        os.makedirs(library, exist_ok=True)
        with open(os.path.join(library, "good.json"), "w") as f:
            json.dump({"format_version": 1, "name": "good rubber", "category": "silicone",
                       "engine": "e", "youngs_modulus_pa": {"value": 1e5, "source": "s"},
                       "poisson_ratio": {"value": 0.3, "source": "s"},
                       "density_kg_m3": {"value": 1000, "source": "s"}}, f)
        with open(os.path.join(library, "bad.json"), "w") as f:
            json.dump({"format_version": 1, "name": "x"}, f)
        uses_good = small_experiment()
        uses_good["materials"][0] = {"library": "good"}
        path = os.path.join(self.dir, "uses-good.json")
        with open(path, "w") as f:
            json.dump(uses_good, f)
        old = os.environ.get("BHM_MATERIALS_DIR")
        os.environ["BHM_MATERIALS_DIR"] = library
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                self.assertEqual(bhm.validate(path), [])
                bhm.simulate(uses_good, BODY, seconds=0.01)
            env = dict(os.environ)
            done = subprocess.run([BHM, "validate", path], capture_output=True, text=True,
                                  env=env)
        finally:
            if old is None:
                del os.environ["BHM_MATERIALS_DIR"]
            else:
                os.environ["BHM_MATERIALS_DIR"] = old
        printed = [line[len("bhm: warning: "):] for line in done.stderr.splitlines()
                   if line.startswith("bhm: warning: ")]
        self.assertTrue(printed, done.stderr)
        said = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
        self.assertEqual(said, printed * 2)  # validate, then simulate
        self.assertTrue(any("bad.json" in line for line in said))


class Runs(Fixture):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.run_dir = os.path.join(cls.dir, "run")
        status, text = run_cli("evolve", cls.experiment_path, "--out", cls.run_dir,
                               "--threads", "1", "--seed", "3")
        assert status == 0, text

    def test_load_run_matches_the_files(self):
        run = bhm.load_run(self.run_dir)
        with open(os.path.join(self.run_dir, "fitness.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(set(run["fitness"]), set(rows[0]))
        for column, values in run["fitness"].items():
            self.assertIsInstance(values, np.ndarray)
            np.testing.assert_array_equal(values, [float(r[column]) for r in rows])
        self.assertEqual(len(run["fitness"]["generation"]), 2)
        with open(os.path.join(self.run_dir, "population.csv")) as f:
            members = list(csv.DictReader(f))
        self.assertEqual(set(run["population"]), set(members[0]))
        for column, values in run["population"].items():
            np.testing.assert_array_equal(values, [float(r[column]) for r in members])
        with open(os.path.join(self.run_dir, "champion.json")) as f:
            champion = json.load(f)
        self.assertEqual(run["champion"], champion)
        self.assertGreaterEqual(len(run["champions"]), 1)
        self.assertEqual(run["champions"][-1], champion)
        self.assertEqual(run["rule_changes"], [])
        self.assertEqual(run["seed"], 3)
        with self.assertRaises(ValueError):
            bhm.load_run(os.path.join(self.dir, "no-such-run"))

    def test_decode_gives_the_champion_phenotype(self):
        run = bhm.load_run(self.run_dir)
        champion = run["champion"]
        body = bhm.decode(run["experiment"], champion["genome"])
        self.assertEqual(body, champion["phenotype"])
        self.assertEqual(bhm.decode(run["experiment"], json.dumps(champion["genome"])), body)
        self.assertEqual(bhm.decode(run["experiment"], champion), body)
        with self.assertRaises(ValueError):
            bhm.decode(run["experiment"], {"nodes": "nonsense"})


class Limits(unittest.TestCase):
    """The module applies the command line's limits, checks its arguments and can be interrupted
    (issue 26 N2, N3, N7)."""

    def test_endless_durations_are_refused_as_the_command_line_refuses_them(self):
        e = small_experiment()
        for seconds in (math_inf := float("inf"), -math_inf, float("nan"), 1e300, 1e6, 0.0, -1.0):
            with self.assertRaises(ValueError, msg=str(seconds)) as caught:
                bhm.simulate(e, BODY, seconds=seconds)
            self.assertIn("seconds", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            bhm.simulate(e, BODY, seconds=1e6)
        budget = str(caught.exception)
        self.assertIn("cannot simulate 1e+06 s: needs ", budget)
        with tempfile.TemporaryDirectory() as d:
            for name, doc in (("e.json", e), ("b.json", BODY)):
                with open(os.path.join(d, name), "w") as f:
                    json.dump(doc, f)
            code, out = run_cli("simulate", os.path.join(d, "e.json"), "--body",
                                os.path.join(d, "b.json"), "--seconds", "1e6", "--out",
                                os.path.join(d, "out"))
        self.assertEqual(code, 1)
        self.assertIn(budget[budget.index("cannot simulate"):], out)

    def test_arguments_of_the_wrong_type_are_type_errors(self):
        e = small_experiment()
        for call in (lambda: bhm.validate({"size": [1, 1, 1]}), lambda: bhm.validate(42),
                     lambda: bhm.simulate(e, 3.5), lambda: bhm.simulate(None, BODY),
                     lambda: bhm.load_run(["run"]), lambda: bhm.simulate(e, BODY, seconds={})):
            with self.assertRaises(TypeError):
                call()
        self.assertEqual(bhm.validate(pathlib.Path(QUICK_DEMO)), [])
        with self.assertRaises(TypeError) as caught:
            bhm.simulate({"simulation": {1, 2}}, BODY)
        self.assertIn("<experiment dict>", str(caught.exception))

    def test_json_problems_read_as_messages_not_library_codes(self):
        e = small_experiment()
        e["simulation"]["settle_s"] = float("nan")
        with self.assertRaises(ValueError) as caught:
            bhm.simulate(e, BODY)
        self.assertIn("<experiment dict>: not valid JSON", str(caught.exception))
        self.assertNotIn("json.exception", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            bhm.decode(QUICK_DEMO, "{\"nodes\": [1, 2")
        self.assertNotIn("json.exception", str(caught.exception))

    def test_too_few_samples_are_refused(self):
        e = small_experiment()
        e["simulation"]["record_fps"] = 0.001  # gave 2 samples and "max displacement 0"
        with self.assertRaises(ValueError) as caught:
            bhm.simulate(e, BODY)
        self.assertIn("simulation.record_fps 0.001 records no sample between the start and the end",
                      str(caught.exception))

    def test_endless_files_are_refused_by_name(self):
        problems = bhm.validate("/dev/zero")
        self.assertEqual(len(problems), 1)
        self.assertIn("/dev/zero:(file): is not a regular file", problems[0])

    def test_ctrl_c_interrupts_a_long_simulation_within_a_second(self):
        e = small_experiment()
        with self.assertRaises(ValueError) as caught:
            bhm.simulate(e, BODY, seconds=1e6)
        # The longest simulation the budget allows (half of it): minutes to hours of wall time.
        dt = float(re.search(r"steps of ([0-9.e+-]+) s", str(caught.exception)).group(1))
        seconds = 0.5 * 1e8 * dt
        e["simulation"]["record_fps"] = 25  # few samples: polling must not wait for them
        sent = []

        def interrupt():
            time.sleep(0.5)
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)

        threading.Thread(target=interrupt, daemon=True).start()
        with self.assertRaises(KeyboardInterrupt):
            bhm.simulate(e, BODY, seconds=seconds)
        self.assertTrue(sent, "the simulation ended before the interrupt")
        self.assertLess(time.monotonic() - sent[0], 1.0)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
