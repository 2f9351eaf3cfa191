"""OpenQuake hazardlib's BooreEtAl2014 (BSSA14) for PGA on a grid of (M, R_JB, Vs30), for test_prior's peer test.

Usage: peer_bssa14.py '[[M, rjb_km, vs30_m_s], ...]'. Prints JSON {"ln_mean": [...], "sigma": [...], "tau": [...],
"phi": [...]}: hazardlib's mean of ln PGA (g) and its total, between- and within-event standard deviations, with the
style of faulting unspecified (sof=False: e0) and the basin term off (region='nobasin', the default).
"""
import json
import sys

import numpy as np
from openquake.hazardlib.gsim.boore_2014 import BooreEtAl2014
from openquake.hazardlib.imt import PGA


def main():
    grid = json.loads(sys.argv[1])
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
    print(json.dumps({"ln_mean": mean[0].tolist(), "sigma": sig[0].tolist(), "tau": tau[0].tolist(),
                      "phi": phi[0].tolist()}))


if __name__ == "__main__":
    main()
