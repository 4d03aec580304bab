"""The 2D jet of scenes/jet2d.ini on both backends, from Python: packing fraction and granular
temperature across layer (a), the layer on the target (model §6), as docs/python.md shows.

    PYTHONPATH=build/python /usr/bin/python3 examples/jet2d_layer_a.py [OUT_DIR]

Writes OUT_DIR/jet2d_soft_dem.h5, jet2d_event_driven.h5 and jet2d_layer_a.png (default: .)."""
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import granjet  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
scene = granjet.Scene.from_file(str(Path(__file__).parent.parent / "scenes" / "jet2d.ini"))
fig, (ax_phi, ax_t) = plt.subplots(1, 2, figsize=(8, 3.2), sharex=True)
for backend in ("soft_dem", "event_driven"):
    summary = granjet.Simulator(scene, backend).run(str(out / f"jet2d_{backend}.h5"))
    run = granjet.open(summary["output"])
    y = run.dataset("/fields/layout/y")[0]  # bin centres across the jet; layer (a) is row 0
    for ax, field in ((ax_phi, "phi"), (ax_t, "T_g")):
        ax.plot(y, run.fields[field]["mean"][0], "o-", label=backend)
ax_phi.set(xlabel="y / d", ylabel=r"$\phi$ in layer (a)")
ax_t.set(xlabel="y / d", ylabel=r"$T_g$ in layer (a)")
ax_phi.legend()
fig.tight_layout()
fig.savefig(out / "jet2d_layer_a.png", dpi=120)
