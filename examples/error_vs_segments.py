"""The error of the meshed render against the analytic one as the angular
segments N grow, and its fitted slope (docs/python.md). Usage:
    error_vs_segments.py [OUT.png [WIDTH HEIGHT SPP [SCENE.xml]]]"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import celadon

out = sys.argv[1] if len(sys.argv) > 1 else "error-vs-segments.png"
width, height, spp = map(int, sys.argv[2:5]) if len(sys.argv) > 4 else (320, 180, 16)
segments = [8, 16, 32, 64, 128, 256]
studio = os.path.join(os.path.dirname(__file__), "..", "scenes", "studio", "scene.xml")
scene = celadon.load_scene(sys.argv[5] if len(sys.argv) > 5 else studio)
render = lambda geometry: scene.render(spp=spp, res=(width, height), seed=1, geometry=geometry)[..., :3]
analytic = render("analytic").astype(np.float64)
errors = [np.abs(render(f"mesh:{n}") - analytic).mean() for n in segments]
slope, intercept = np.polyfit(np.log10(segments), np.log10(errors), 1)
print(f"fitted slope {slope:.4f}")
plt.loglog(segments, errors, "o", label="mean |meshed - analytic|")
plt.loglog(segments, 10 ** intercept * np.array(segments, float) ** slope, label=f"fit: slope {slope:.2f}")
plt.xlabel("angular segments N"), plt.ylabel("image error")
plt.title(f"{os.path.basename(os.path.dirname(scene.path))}, {width}x{height}, {spp} spp")
plt.legend()
plt.savefig(out, dpi=100)
