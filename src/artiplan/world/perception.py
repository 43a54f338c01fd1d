"""Perception: a virtual overhead camera that sees each link's 6D pose with noise, and the
estimation step that turns several noisy frames into a configuration with uncertainties.

Measurement model (per frame, per link i): the link's centre c_i [m] with isotropic Gaussian
noise (``position_sigma_m``) and its orientation with a Gaussian rotation-vector error
(``orientation_sigma_deg`` per axis). Estimation: a weighted linear least squares over the link
directions u_i, using both the observed axes (u_i ~ axis_i) and the chain geometry
(c_i = base + L * (u_1 + ... + u_{i-1}) + L/2 * u_i, the base end of L1 being known: it is the
fixture). Averaging the frames first is the same estimate (the problem is linear). The estimated
directions are normalised and converted to (theta, gamma), choosing the double-cover
representation nearest the reference (a prediction or the previous estimate).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from artiplan.model import Configuration
from artiplan.world.rotations import Vec, configuration_from_directions


@dataclass(frozen=True)
class PerceptionConfig:
    """Noise and estimation settings of the virtual camera.

    Attributes:
        position_sigma_m: Std. dev. of each link centre's position, per axis [m].
        orientation_sigma_deg: Std. dev. of each link's orientation error, per axis [deg].
        frames: Number of frames the estimate combines (taken at one instant: independent noise).
        use_positions: Fuse the centre positions with the orientations (else orientations only).
    """

    position_sigma_m: float = 0.005
    orientation_sigma_deg: float = 2.0
    frames: int = 64
    use_positions: bool = True

    def __post_init__(self) -> None:
        if self.position_sigma_m < 0 or self.orientation_sigma_deg < 0:
            raise ValueError("noise sigmas must be >= 0")
        if self.frames < 1:
            raise ValueError("frames must be >= 1")


@dataclass(frozen=True)
class Percept:
    """What perception reports at one time.

    Attributes:
        time: Simulation time of the observation [s].
        configuration: Estimated configuration (covers chosen near the reference).
        uncertainty_deg: Per link, the estimate's standard error as a direction angle [deg]
            (L1, the clamped base, included).
    """

    time: float
    configuration: Configuration
    uncertainty_deg: tuple[float, ...]


def _random_rotations(rng: np.random.Generator, n: int, sigma_rad: float) -> Vec:
    """(n, 3, 3) rotation matrices from Gaussian rotation vectors (Rodrigues, vectorised)."""
    rv = rng.normal(0.0, sigma_rad, size=(n, 3))
    angle = np.linalg.norm(rv, axis=1)
    k = rv / np.where(angle > 1e-12, angle, 1.0)[:, None]
    kx = np.zeros((n, 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    kx[:, 1, 0], kx[:, 2, 0], kx[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3)[None] + s * kx + (1.0 - c) * (kx @ kx)


def observe(
    centres: Vec, axes: Vec, cfg: PerceptionConfig, rng: np.random.Generator
) -> tuple[Vec, Vec]:
    """Noisy frames: (frames, n, 3) centres and (frames, n, 3) link axes (unit directions)."""
    n = len(centres)
    c = centres[None, :, :] + rng.normal(0.0, cfg.position_sigma_m, size=(cfg.frames, n, 3))
    rots = _random_rotations(rng, cfg.frames * n, math.radians(cfg.orientation_sigma_deg))
    a = np.einsum("fnij,nj->fni", rots.reshape(cfg.frames, n, 3, 3), axes)
    return c, a


def estimate(
    centres: Vec,
    axes: Vec,
    base: Vec,
    link_length: float,
    cfg: PerceptionConfig,
    reference: Configuration | None = None,
) -> tuple[Configuration, tuple[float, ...]]:
    """Least-squares link directions from noisy frames; returns (configuration, uncertainty).

    ``centres`` and ``axes`` are (frames, n, 3); ``base`` is the known base end of L1 [m].
    """
    frames, n, _ = axes.shape
    mean_c = centres.mean(axis=0)
    mean_a = axes.mean(axis=0)
    # Tiny floors keep the weights finite when a sigma is zero (a noise-free camera).
    var_a = max(math.radians(cfg.orientation_sigma_deg) ** 2, 1e-12) / frames
    var_c = max(cfg.position_sigma_m**2, 1e-12) / frames
    # Per coordinate the problem is the same n x n system: unknown u_i[x], rows = observations.
    rows_a = np.eye(n)
    rows_c = np.zeros((n, n))
    for i in range(n):
        rows_c[i, :i] = link_length
        rows_c[i, i] = link_length / 2.0
    if cfg.use_positions:
        design = np.vstack([rows_a / math.sqrt(var_a), rows_c / math.sqrt(var_c)])
        obs = np.vstack([mean_a / math.sqrt(var_a), (mean_c - base) / math.sqrt(var_c)])
    else:
        design, obs = rows_a / math.sqrt(var_a), mean_a / math.sqrt(var_a)
    normal = design.T @ design
    cov = np.linalg.inv(normal)  # per-coordinate covariance of the u_i [1/rad^2 units]
    u = np.linalg.solve(normal, design.T @ obs)
    norms = np.linalg.norm(u, axis=1, keepdims=True)
    dirs = u / np.where(norms > 0, norms, 1.0)
    # A direction has two free components: angular std. error ~ sqrt(2 * var) / |u|.
    sigma = np.degrees(np.sqrt(2.0 * np.diag(cov)) / np.maximum(norms[:, 0], 1e-9))
    conf = configuration_from_directions(dirs, reference)
    return conf, tuple(float(s) for s in sigma)
