"""OpenQuake hazardlib's BooreEtAl2014 (BSSA14) for PGA on a grid of (M, R_JB, Vs30), for test_prior's peer tests.

Usage: peer_bssa14.py '[[M, rjb_km, vs30_m_s], ...]'. Prints JSON {"ln_mean": [...], "sigma": [...], "tau": [...],
"phi": [...]}: hazardlib's mean of ln PGA (g) and its total, between- and within-event standard deviations, with the
style of faulting unspecified (sof=False: e0) and the basin term off (region='nobasin', the default).

peer_bssa14.py --table: the same for test_prior's grid (GRID below, the test checks that its own grid is this one),
with hazardlib's version, written to tests/peer/bssa14_hazardlib.json: the peer's table that the test command compares
against, so that it need not install OpenQuake (about two minutes, most of it numba). Regenerate it with
TOPPLE_TEST_HAZARDLIB=1 scripts/test-venv.sh && .venv-test/bin/python tests/peer/peer_bssa14.py --table.
"""
import json
import pathlib
import sys

import numpy as np
from openquake.hazardlib.gsim.boore_2014 import BooreEtAl2014
from openquake.hazardlib.imt import PGA

# test_prior's grid over the model's range: M 3.5-8 (both sides of Mh = 5.5 and of the tau/phi hinges 4.5, 5.5), R_JB
# 0-300 km (both sides of R1 = 110 and R2 = 270), Vs30 150-2000 m/s (soft soil with strong F_nl, the phi hinges
# 225/300, Vref, beyond Vc).
GRID = [[m, r, v] for m in (3.5, 4.5, 5.0, 5.5, 6.0, 6.7, 7.5, 8.0)
        for r in (0.0, 3.0, 10.0, 30.0, 80.0, 150.0, 300.0)
        for v in (150.0, 250.0, 300.0, 450.0, 760.0, 1200.0, 2000.0)]


def hazardlib_pga(grid):
    n = len(grid)
    ctx = np.recarray(n, dtype=[("mag", float), ("rake", float), ("rjb", float), ("vs30", float),
                                ("z1pt0", float)])
    ctx.mag = [g[0] for g in grid]
    ctx.rake = 0.0
    ctx.rjb = [g[1] for g in grid]
    ctx.vs30 = [g[2] for g in grid]
    ctx.z1pt0 = -999.0
    gsim = BooreEtAl2014(sof=False)
    mean, sig, tau, phi = (np.zeros((1, n)) for _ in range(4))
    gsim.compute(ctx, [PGA()], mean, sig, tau, phi)
    return {"ln_mean": mean[0].tolist(), "sigma": sig[0].tolist(), "tau": tau[0].tolist(), "phi": phi[0].tolist()}


def main():
    if sys.argv[1:] == ["--table"]:
        from importlib.metadata import version
        table = {"source": "OpenQuake hazardlib BooreEtAl2014(sof=False), PGA, z1pt0 = -999 (no basin term); "
                           "written by tests/peer/peer_bssa14.py --table",
                 "openquake_engine_version": version("openquake.engine"), "numpy_version": np.__version__,
                 "grid_m_rjb_km_vs30_m_s": GRID}
        table.update(hazardlib_pga(GRID))
        out = pathlib.Path(__file__).with_name("bssa14_hazardlib.json")
        # One key a line, each array on its line: a diff of a regenerated table shows which arrays changed.
        out.write_text("{\n" + ",\n".join(f" {json.dumps(k)}: {json.dumps(v)}" for k, v in table.items()) + "\n}\n")
        print(f"wrote {out} ({len(GRID)} points)")
        return
    print(json.dumps(hazardlib_pga(json.loads(sys.argv[1]))))


if __name__ == "__main__":
    main()
