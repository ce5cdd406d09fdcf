"""Numbers of a run's samples (orthocontact.identification.samples): the
sensor's noise from consecutive differences, whatever steps, resolution or
drift the log has; the speed a tracked coordinate reaches; the longest
stretch of a mask."""
import numpy as np
import pytest

from orthocontact.identification.samples import longest_true, mean_se, noise_sd, peak_speed


def test_noise_sd_finds_white_noise_through_steps_and_drift():
    rng = np.random.default_rng(1)
    noise = rng.normal(0.0, 0.05, 4000)
    steps = np.where(np.arange(4000) % 500 < 250, 0.0, 12.0)    # a pull starting and stopping 8 times
    drift = 0.02 * np.linspace(0.0, 16.0, 4000)
    assert noise_sd(noise) == pytest.approx(0.05, rel=0.05)
    assert noise_sd(noise + steps + drift) == pytest.approx(0.05, rel=0.05)


def test_noise_sd_does_not_jump_where_the_resolution_is_the_noise():
    """A log's last digit about its noise (a force in kN to 4 decimals):
    the estimate stays within a factor 1.5, where a median of the
    differences would give 0 or twice the noise."""
    noise = np.random.default_rng(2).normal(0.0, 5e-5, 4000)
    for resolution in (2e-5, 5e-5, 1e-4):
        assert 0.67 < noise_sd(np.round(noise / resolution) * resolution) / 5e-5 < 1.5


def test_noise_sd_over_a_mask_and_too_few_samples():
    F = np.r_[np.zeros(50), np.full(50, 5.0)] + np.random.default_rng(3).normal(0.0, 0.1, 100)
    assert noise_sd(F, F < 2.5) == pytest.approx(0.1, rel=0.3)
    assert np.isnan(noise_sd(np.arange(5.0)))


def test_peak_speed_is_the_cruise_not_the_spikes():
    t = np.linspace(0.0, 2.0, 401)
    x = np.clip(0.244 * (t - 0.25), 0.0, 0.3)
    x[200] += 0.01     # one wild sample
    assert peak_speed(t, x) == pytest.approx(0.244, rel=1e-6)
    assert np.isnan(peak_speed(t[:3], x[:3]))


def test_longest_true_and_mean_se():
    assert longest_true(np.array([1, 0, 1, 1, 1, 0, 1, 1], bool)) == (2, 5)
    assert longest_true(np.zeros(4, bool)) == (0, 0)
    m, se = mean_se([1.0, 2.0, 3.0])
    assert (m, se) == (2.0, pytest.approx(1 / np.sqrt(3)))
    assert mean_se([4.0])[1] == np.inf
