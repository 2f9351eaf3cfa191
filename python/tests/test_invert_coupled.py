"""topple.invert on objects that slid and rocked (issue 15): the coupled outcomes and `model` pass through the dict
survey unchanged, and a bad combination is refused with its field, as from a file."""
import copy

import pytest

import topple

SURVEY = {
    "inversion": {"pga_g": [0.1, 1.5, 4], "freq_hz": [1.0, 4.0, 2], "motions_per_cell": 3, "duration_s": 6.0},
    "object": [
        {"id": "bottle", "width": "10cm", "height": "30cm", "mu": [0.2, 0.3], "outcome": "slid_stood", "slid": "2cm"},
        {"id": "clock", "width": "12cm", "height": "30cm", "mu": 0.45, "outcome": "rocked", "model": "coupled"},
        {"id": "pan", "width": "25cm", "height": "12cm", "mu": 0.25, "outcome": "slid"},
    ],
}


def test_invert_takes_the_coupled_outcomes_and_says_the_model():
    result = topple.invert(SURVEY, threads=2)
    by_id = {o["id"]: o for o in result["objects"]}
    assert by_id["bottle"]["outcome"] == "slid_stood" and by_id["bottle"]["model"] == "coupled"
    assert by_id["clock"]["outcome"] == "rocked" and by_id["clock"]["model"] == "coupled"
    assert "model" not in by_id["pan"]  # the sliding block, as before the coupled model


def test_a_coupled_outcome_on_the_rocking_model_is_refused_with_its_field():
    bad = copy.deepcopy(SURVEY)
    bad["object"][0]["outcome"] = "walked"
    bad["object"][0].pop("slid")
    bad["object"][0]["model"] = "rock"
    with pytest.raises(topple.InputError) as err:
        topple.invert(bad)
    assert err.value.field == "object[1](bottle).model"
    assert "<survey dict>" in str(err.value)
