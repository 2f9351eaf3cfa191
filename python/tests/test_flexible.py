"""topple.slide_flexible gives the CLI's JSON (`topple slide --support-freq|--height --json`) for the same inputs,
bit for bit apart from the "input" object (the CLI names the file, Python the motion), and refuses bad input."""
import pytest

import topple
from conftest import shared_record

CASES = [
    ({"mu": 0.1, "support_freq_hz": 4.0, "support_damping": 0.05},
     ["--mu", "0.1", "--support-freq", "4Hz", "--support-damping", "5%"]),
    ({"mu": 0.1, "support_freq_hz": 4.0, "mass_ratio": 0.2, "coupled": True},
     ["--mu", "0.1", "--support-freq", "4Hz", "--mass-ratio", "0.2", "--coupled"]),
    ({"mu": 0.1, "mode": "one-way", "height_m": 50.0, "vs_slope_m_s": 600.0, "vs_base_m_s": 600.0, "damping": 0.05,
      "reference_strain": 0.0005, "coupled": True},
     ["--mu", "0.1", "--one-way", "--height", "50m", "--vs-slope", "600", "--vs-base", "600", "--damping", "5%",
      "--ref-strain", "0.05%", "--coupled"]),
]


def without_input(d):
    return {k: v for k, v in d.items() if k != "input"}


@pytest.mark.parametrize("kwargs,args", CASES)
def test_slide_flexible_equals_cli(cli, kwargs, args):
    record = shared_record("RSN6_IMPVALL.I_I-ELC180.AT2")
    expected = cli.json("slide", record, *args)
    result = topple.slide_flexible(topple.read(record), **kwargs)
    assert without_input(result) == without_input(expected)
    assert result["support"]["analysis"] == ("coupled" if kwargs.get("coupled") else "decoupled")


def test_slide_flexible_rejects_bad_input(made_record):
    motion = topple.read(made_record)
    with pytest.raises(topple.InputError, match="either support_freq_hz"):
        topple.slide_flexible(motion, mu=0.1)
    with pytest.raises(topple.InputError, match="got 0 Hz"):
        topple.slide_flexible(motion, mu=0.1, support_freq_hz=0.0)
    with pytest.raises(topple.InputError, match="needs vs_slope_m_s"):
        topple.slide_flexible(motion, mu=0.1, height_m=10.0)
