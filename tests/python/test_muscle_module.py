"""The bhm Python module on a muscle experiment (issue 43): the muscle-catheter preset and its body
simulate from Python, the muscle voxels' activation follows the first-order activation dynamics
solved here from the experiment's own fields, and the catheter shortens only once the stimulus
starts, by about what the rule of mixtures says, and comes back toward rest between bursts.

Run by ctest as: python3 test_muscle_module.py BHM_EXECUTABLE SOURCE_DIR (PYTHONPATH=build/python).
"""
import copy
import json
import math
import os
import sys
import unittest

import numpy as np

import bhm

SOURCE = sys.argv[2]
PRESET = os.path.join(SOURCE, "assets", "experiments", "muscle-catheter.json")
BODY = os.path.join(SOURCE, "assets", "bodies", "muscle-catheter.body.json")


def stimulated(m, tau):
    """The pulse train of docs/physics.md, "Muscle actuation": pulses of pulse_width_s every
    1 / frequency_hz, in bursts of train_on_s separated by train_off_s (0: one endless train)."""
    if tau < 0.0:
        return False
    on, off = m.get("train_on_s", 0.0), m.get("train_off_s", 0.0)
    if off > 0.0:
        tau = math.fmod(tau, on + off)
        if tau >= on:
            return False
    return math.fmod(tau, 1.0 / m["frequency_hz"]) < m["pulse_width_s"]


def activation(m, taus, h=1e-5):
    """a(tau) of da/dt = (1 - a) / rise_s while stimulated, -a / decay_s otherwise, a(0) = 0:
    marched in steps of h, each solved exactly for the stimulus at its middle (the pulses' edges
    fall on multiples of 10 ms, so the steps do not straddle them but for round-off)."""
    out, a, tau = [], 0.0, 0.0
    grow, fall = math.exp(-h / m["rise_s"]), math.exp(-h / m["decay_s"])
    for target in taus:
        while tau + h <= target + 1e-12:
            a = 1.0 - (1.0 - a) * grow if stimulated(m, tau + 0.5 * h) else a * fall
            tau += h
        rest = max(0.0, target - tau)  # the part step to the frame's time
        if stimulated(m, tau + 0.5 * rest):
            out.append(1.0 - (1.0 - a) * math.exp(-rest / m["rise_s"]))
        else:
            out.append(a * math.exp(-rest / m["decay_s"]))
    return np.array(out)


class MuscleCatheter(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(PRESET) as f:
            cls.experiment = json.load(f)
        cls.experiment["simulation"]["record_fps"] = 200  # frames every 5 ms
        cls.muscle = cls.experiment["materials"][1]["muscle"]
        cls.result = bhm.simulate(cls.experiment, BODY)
        # The same body with a muscle 1e5 times weaker (0 would make the experiment passive,
        # which evolution refuses): its bend is 1e5 times smaller, so it shows the body's
        # settling under gravity alone.
        still = copy.deepcopy(cls.experiment)
        still["materials"][1]["muscle"]["contraction_strain"] *= 1e-5
        cls.still = bhm.simulate(still, BODY)

    def test_activation_follows_the_first_order_dynamics(self):
        r, m = self.result, self.muscle
        settle = self.experiment["simulation"]["settle_s"]
        size = r["summary"]["voxel_size_m"]
        is_muscle = r["voxel_material"] == 2
        self.assertGreater(is_muscle.sum(), 0)
        sizes = r["sizes"][:, is_muscle, :].astype(np.float64)
        # Every muscle voxel has one activation: the same sizes, axis by axis.
        np.testing.assert_allclose(sizes, sizes[:, :1, :].repeat(sizes.shape[1], axis=1),
                                   rtol=0, atol=1e-9)
        along, across = sizes[:, 0, 0] / size, sizes[:, 0, 1] / size
        strain = m["contraction_strain"]
        nu = self.experiment["materials"][1]["poisson_ratio"]
        measured = (1.0 - along) / strain
        tau = r["frame_t"] - settle
        expected = np.where(tau > 0, activation(m, np.maximum(tau, 0.0)), 0.0)
        # float32 sizes of a 2 mm voxel: 1e-7 of it, divided by the strain 0.1.
        np.testing.assert_allclose(measured, expected, rtol=0, atol=1e-5)
        # Across the fibre the voxel widens by nu times the shortening.
        np.testing.assert_allclose(across - 1.0, nu * strain * expected, rtol=0, atol=1e-6)
        # The twitches sum toward tetanus (the preset says about 0.7 at 50 Hz) and relax between
        # bursts: a check that the case is not trivial.
        self.assertGreater(expected.max(), 0.6)
        self.assertLess(expected.max(), 0.8)
        rest_end = (tau > 0.49) & (tau < 0.5)
        self.assertTrue(rest_end.any())
        self.assertLess(expected[rest_end].max(), 0.06)

    def test_the_body_shortens_only_once_stimulated_and_comes_back_in_the_rest(self):
        r, s, m = self.result, self.still, self.muscle
        settle = self.experiment["simulation"]["settle_s"]
        np.testing.assert_array_equal(r["t"], s["t"])
        tau = r["t"] - settle
        moved = r["tip"] - s["tip"]  # the muscle's doing: the same body, practically still, less
        distance = np.linalg.norm(moved, axis=1)
        # The end of the first burst (0.3 s of 50 Hz pulses): the twitches have fused into a
        # plateau whose mean activation the first-order dynamics give. The tip still follows the
        # 50 Hz ripple, so its mean is taken over one pulse period: 4 frames 5 ms apart.
        def period(start):
            return (tau > start - 0.0025) & (tau < start + 0.0175)

        plateau = period(0.28)
        self.assertEqual(plateau.sum(), 4)
        mean_a = activation(m, np.arange(0.28, 0.3, 1e-4)).mean()
        # Independent estimate of the tip's shortening: the muscle's free strain shared with
        # the sheath as parallel springs along x (rule of mixtures: E A of the 2 muscle voxels of
        # the 16 in a cross-section against the Ecoflex's), over the length from the clamped
        # voxels' centres to the tip's.
        e_muscle = self.library("skeletal-muscle-engineered")["youngs_modulus_pa"]["value"]
        e_sheath = self.library("ecoflex-00-30")["youngs_modulus_pa"]["value"]
        is_muscle = r["voxel_material"] == 2
        share = e_muscle * is_muscle.sum() / (e_muscle * is_muscle.sum() +
                                              e_sheath * (~is_muscle).sum())
        fixed_x = r["positions"][0, r["voxel_fixed"].astype(bool), 0].mean()
        length = s["tip"][0, 0] - fixed_x
        estimate = m["contraction_strain"] * mean_a * share * length
        shortening = -moved[plateau, 0].mean()
        print(f"\ntip shortening {shortening * 1e6:.2f} um, rule of mixtures {estimate * 1e6:.2f} "
              f"um (mean activation {mean_a:.3f})", file=sys.stderr)
        # The estimate lets the muscle widen freely across its fibres (by nu = 0.49 times its
        # shortening); the sheath holds that widening back, which through the Poisson effect
        # lengthens the muscle again, so the estimate is an upper bound (the clamp at x- holds
        # the layers' ends too). Measured: about 0.7 of it; the bounds leave room either side.
        self.assertGreater(shortening, 0.5 * estimate)
        self.assertLess(shortening, 1.05 * estimate)
        peak = distance[plateau].max()
        # Shortening along the fibres is the largest part of the motion (the tip also rises:
        # the muscle below the middle widens and pushes the layers above it up).
        along = -moved[plateau, 0]
        self.assertTrue(np.all(along > np.abs(moved[plateau, 1])))
        self.assertTrue(np.all(along > np.abs(moved[plateau, 2])))
        # Before the stimulus the two bodies settle alike (their steps differ a little: a muscle
        # that may contract further sets a shorter stable step) ...
        self.assertLess(distance[tau < 0].max(), 0.01 * peak)
        # ... and the first twitches move the tip at once.
        self.assertGreater(distance[(tau > 0) & (tau <= 0.02)].max(), 0.3 * peak)
        # In the 0.2 s of rest after the burst the activation decays (decay_s 0.06 s) to a few
        # percent: the tip comes back toward rest all along, to under a quarter of the plateau
        # (the soft body's own relaxation lags the activation).
        rest = (tau > 0.3) & (tau < 0.5)
        self.assertTrue(np.all(np.diff(-moved[rest, 0]) < 0.01 * peak))
        self.assertLess(distance[(tau > 0.45) & (tau < 0.5)].max(), 0.25 * peak)
        # The next burst shortens it again as far.
        second = period(0.73)
        self.assertEqual(second.sum(), 4)
        self.assertGreater(-moved[second, 0].mean(), 0.9 * shortening)

    @staticmethod
    def library(name):
        with open(os.path.join(SOURCE, "assets", "materials", name + ".json")) as f:
            return json.load(f)

if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
