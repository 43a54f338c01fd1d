"""Perception: noisy 6D link poses, estimation over frames, double-cover choice."""

from __future__ import annotations

import random

import numpy as np

from artiplan.model import ArticulatedObject, Configuration, direction_error, random_configuration
from artiplan.world.perception import PerceptionConfig
from artiplan.world.rotations import direction, nearest_cover
from artiplan.world.scene import World, WorldConfig


def test_filtered_estimate_within_one_degree_at_5mm_2deg() -> None:
    for n in (4, 8, 12):
        obj = ArticulatedObject(n)
        for seed in range(10):
            conf = random_configuration(n, random.Random(seed))
            cfg = PerceptionConfig(position_sigma_m=0.005, orientation_sigma_deg=2.0, frames=64)
            world = World(obj, conf, WorldConfig(perception=cfg, seed=seed))
            percept = world.perceive(reference=conf)
            err = direction_error(percept.configuration, conf)
            assert err.max() < 1.0, (n, seed, err)
            # The reported uncertainty is of the right size (RMS, not a bound).
            assert 0.05 < float(np.mean(percept.uncertainty_deg)) < 1.0


def test_one_noisy_frame_is_worse_than_the_filtered_estimate() -> None:
    obj = ArticulatedObject(8)
    conf = random_configuration(8, random.Random(3))
    one = PerceptionConfig(frames=1)
    world = World(obj, conf, WorldConfig(seed=1))
    errs_one = [
        direction_error(world.perceive(conf, one).configuration, conf).mean() for _ in range(20)
    ]
    errs_many = [
        direction_error(world.perceive(conf).configuration, conf).mean() for _ in range(20)
    ]
    assert np.mean(errs_many) < 0.5 * np.mean(errs_one)


def test_zero_noise_is_exact_and_keeps_the_reference_cover() -> None:
    obj = ArticulatedObject(6)
    conf = random_configuration(6, random.Random(11))
    world = World(obj, conf)
    exact = PerceptionConfig(position_sigma_m=0.0, orientation_sigma_deg=0.0, frames=1)
    p = world.perceive(conf, exact)
    assert np.allclose(p.configuration.theta, conf.theta, atol=1e-5)
    assert np.allclose(p.configuration.gamma, conf.gamma, atol=1e-5)


def test_nearest_cover_picks_the_representation_near_the_reference() -> None:
    u = direction(30.0, 200.0)  # the same direction as (210, 160)
    assert np.allclose(nearest_cover(u, 30.0, 190.0), (30.0, 200.0))
    assert np.allclose(nearest_cover(u, 200.0, 150.0), (210.0, 160.0))
    # At a pole theta is unobservable: the reference's theta is kept.
    t, g = nearest_cover(direction(0.0, 0.0), 123.0, 2.0)
    assert (t, g) == (123.0, 0.0)


def test_hanging_configuration_is_perceived_with_reference_theta() -> None:
    obj = ArticulatedObject(3)
    ref = Configuration.from_angles([40, 50, 60], [0, 0, 0])
    world = World(obj, ref)
    exact = PerceptionConfig(position_sigma_m=0.0, orientation_sigma_deg=0.0, frames=1)
    p = world.perceive(ref, exact)
    assert np.allclose(p.configuration.theta, (40, 50, 60), atol=1e-3)
