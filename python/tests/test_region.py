"""topple.invert_region: the regional joint inversion (issue 17) from Python, against the CLI's `region` and the
example's stated truth."""
import math
import pathlib

import pytest

import topple

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "regional_survey.toml"


@pytest.fixture(scope="module")
def region():
    return topple.invert_region(EXAMPLE, threads=0)


def holds(summary, x):
    low, high = summary["ci95"]
    return low <= x <= high


def test_relation_holds_the_examples_truth(region):
    # The example's header: c0 = 2.36, c1 = 1.2, c2 = 6 km (fixed), tau = 0.3.
    rel = region["relation"]
    assert holds(rel["c1"], 1.2)
    assert holds(rel["c0_ln_g"], 2.36)
    assert holds(rel["tau_ln"], 0.3)
    assert rel["c2_km"] == 6.0


def test_pooled_sites_beside_their_own(region):
    sites = region["sites"]
    assert len(sites) == 12
    station = sites[0]
    # The station's measured 0.573 g with sigma_i = 5 %: its pooled median within 10 %.
    assert station["instrument_pga_g"] == 0.573
    assert station["pooled_pga_g"]["median"] == pytest.approx(0.573, rel=0.1)
    # Pooling borrows strength: on average the pooled 95 % intervals are narrower (in ln PGA) than each site's own,
    # the own intervals' open ends taken at the grid's (0.01 g, 2 g).
    pooled = own = 0.0
    for s in sites[1:]:
        lo, hi = s["pooled_pga_g"]["ci95"]
        pooled += math.log(hi / lo)
        olo, ohi = s["independent_pga_g"]["ci95"]
        own += math.log((ohi if ohi is not None else 2.0) / (olo if olo is not None else 0.01))
    assert pooled < own
    # Each site's own inversion comes along, as topple.invert gives it.
    assert len(region["site_results"]) == 12
    assert region["site_results"][3]["pga_g"]["median"] == sites[3]["independent_pga_g"]["median"]


def test_frequency_relation_not_supported_for_one_frequency(region):
    # The example's motions are all at 3 Hz: a trend with distance must not be supported (Bayes factor < 3), and
    # then no site gets a pooled frequency.
    freq = region["frequency_relation"]
    assert freq["supported"] is False
    assert freq["ln_bayes_factor"] < math.log(3.0)
    assert freq["bayes_factor_threshold"] == 3.0
    assert all(s["pooled_freq_hz"] is None for s in region["sites"])
    assert all(s["independent_freq_hz"]["median"] > 0 for s in region["sites"])


def test_same_as_the_cli(region, cli):
    # The CLI's `region` object, key for key and number for number (the same library call, the same doubles).
    expected = cli.json("invert", EXAMPLE, "--quiet")["region"]
    got = {k: v for k, v in region.items() if k not in ("region_notes", "site_results")}
    assert got == expected


def test_a_survey_without_an_epicentre_is_refused():
    obj = {"id": "b", "shape": "block", "width": "10cm", "height": "40cm", "mu": 0.5, "outcome": "overturned"}
    survey = {"inversion": {"pga_g": [0.05, 2.0, 6], "freq_hz": [2.0, 4.0, 2], "motions_per_cell": 2},
              "sites": [{"name": f"s{i}", "lat": 38.0 + 0.1 * i, "lon": 23.0, "object": [obj]} for i in range(3)]}
    with pytest.raises(topple.InputError, match="epicentre"):
        topple.invert_region(survey)
