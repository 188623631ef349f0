#!/usr/bin/python3
"""Noise per CPU second, celadon against Blender Cycles (docs/BENCHMARKS.md,
"Noise per CPU second"). From the repository root, after `make`:

    /usr/bin/python3 bench/cycles_efficiency.py [--scene studio|cornell-sor|showcase]...
        [--spp 4,16,64] [--res 320x180] [--bin build/celadon]

Each scene is rendered by celadon (scenes/NAME/scene.xml, given a 1-pixel
box filter) and by Cycles (bench/cycles_scene.py: the same scene rebuilt in
Blender, each vessel as celadon's own 360-segment OBJ, a 1-pixel box filter,
no denoising, no adaptive sampling), both on 2 threads, at each spp with
seeds 1 and 2, the two renderers alternating so that they share the machine's load. For each:
MSE = mean((a - b)^2) / 2 over the seed pair (an unbiased renderer's
variance, no reference needed); CPU seconds per spp = the slope of a
least-squares line through the runs' CPU time (user + sys of the child)
against spp, which leaves out each program's start-up and scene build;
efficiency = 1 / (MSE x spp x CPU seconds per spp). The two images' means
must agree (both estimate the same image). Needs blender, python3-numpy and
python3-openimageio (Debian)."""
import argparse
import os
import resource
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

# Each scene's sor shapes: the name Blender finds its OBJ by, the profile
# (under scenes/), the height, and whether the shape has its caps (`caps`
# false: the OBJ loses `celadon mesh`'s base disc).
VESSELS = {
    "studio": [("vessel", "studio/vessel/profile.json", 1.0, True)],
    "cornell-sor": [("vessel", "studio/vessel/profile.json", 1.15, True)],
    "showcase": [("maebyeong", "showcase/maebyeong/profile.json", 0.46, True),
                 ("bowl", "showcase/bowl/profile.json", 0.24, False),
                 ("bottle", "showcase/bottle/profile.json", 0.43, True),
                 ("jar", "showcase/jar/profile.json", 0.38, True)],
}
ROOT = os.getcwd()


def cpu_of(cmd, env=None):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode:
        sys.exit(f"failed: {' '.join(cmd[:4])}: {r.stderr.strip()[-300:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def box_filtered(scene_xml):
    """The scene with a 1-pixel box filter in its film, as Cycles' (the bundled
    scenes take hdrfilm's default Gaussian, which blurs the noise over
    neighbouring pixels: a smaller MSE that is no cleaner an estimate), written
    beside it so that its relative file names resolve."""
    with open(scene_xml) as f:
        xml = f.read()
    film = xml.find("<film")
    end = xml.find(">", film)
    if film < 0 or xml[end - 1] == "/" or "<rfilter" in xml:
        sys.exit(f"{scene_xml}: no <film> to give a box filter, or a filter already")
    out = os.path.join(os.path.dirname(scene_xml), ".efficiency-box.xml")
    with open(out, "w") as f:
        f.write(xml[:end + 1] + '<rfilter type="box"/>' + xml[end + 1:])
    return out


def without_base(obj):
    """Drops the base disc `celadon mesh` adds (every face with its three
    vertices at the lowest height), for a sor declared without caps."""
    with open(obj) as f:
        lines = f.readlines()
    ys = [float(line.split()[2]) for line in lines if line.startswith("v ")]
    low = min(ys)
    keep = []
    for line in lines:
        if line.startswith("f "):
            idx = [int(v.split("/")[0]) for v in line.split()[1:]]
            if all(ys[i - 1] == low for i in idx):
                continue
        keep.append(line)
    with open(obj, "w") as f:
        f.writelines(keep)


def read(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def slope_fit(xs, ys):
    a = np.vstack([np.ones(len(xs)), xs]).T
    return np.linalg.lstsq(a, np.array(ys), rcond=None)[0]  # intercept, slope


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", action="append")
    ap.add_argument("--spp", default="4,16,64")
    ap.add_argument("--res", default="320x180")
    ap.add_argument("--bin", default="build/celadon")
    o = ap.parse_args()
    scenes = o.scene or ["studio", "cornell-sor", "showcase"]
    spps = [int(s) for s in o.spp.split(",")]
    exe = os.path.abspath(o.bin)
    script = os.path.join(ROOT, "bench", "cycles_scene.py")
    tmp = tempfile.mkdtemp(prefix="celadon-cycles-")
    for scene in scenes:
        objdir = os.path.join(tmp, scene)
        os.mkdir(objdir)
        for name, profile, height, caps in VESSELS[scene]:
            obj = os.path.join(objdir, name + ".obj")
            subprocess.run([exe, "mesh", os.path.join(ROOT, "scenes", profile), "-o", obj, "--segments", "360",
                            "--height", str(height)], check=True, capture_output=True)
            if not caps:
                without_base(obj)
        scene_xml = box_filtered(os.path.join(ROOT, "scenes", scene, "scene.xml"))
        runs = {"celadon": {}, "cycles": {}}
        load0 = os.getloadavg()[0]
        for seed in (1, 2):
            for spp in spps:
                out = os.path.join(tmp, f"celadon-{spp}-{seed}.exr")
                c = cpu_of([exe, "render", scene_xml, "-o", out, "--spp",
                            str(spp), "--res", o.res, "--threads", "2", "--seed", str(seed)])
                runs["celadon"][(spp, seed)] = (c, out)
                out = os.path.join(tmp, f"cycles-{spp}-{seed}.exr")
                c = cpu_of(["blender", "-b", "--factory-startup", "--python", script, "--", scene, str(spp), o.res,
                            out, str(seed), objdir])
                runs["cycles"][(spp, seed)] = (c, out)
        os.remove(scene_xml)
        print(f"\n{scene}, {o.res}, 2 threads; load average {load0:.1f} -> {os.getloadavg()[0]:.1f}\n")
        print("| renderer | spp | mean | seed-pair RMSE | rel. | CPU s per spp | efficiency 1/(MSE x CPU s) |")
        print("|---|---:|---:|---:|---:|---:|---:|")
        eff = {}
        for name, r in runs.items():
            xs = [spp for spp in spps for _ in (1, 2)]
            ys = [r[(spp, seed)][0] for spp in spps for seed in (1, 2)]
            intercept, per_spp = slope_fit(xs, ys)
            for spp in spps:
                a, b = read(r[(spp, 1)][1]), read(r[(spp, 2)][1])
                mse = float(np.mean((a - b) ** 2)) / 2.0
                mean = float((a.mean() + b.mean()) / 2.0)
                eff[(name, spp)] = 1.0 / (mse * spp * per_spp)
                print(f"| {name} | {spp} | {mean:.4f} | {np.sqrt(mse):.5f} | {np.sqrt(mse) / mean:.4f} | "
                      f"{per_spp:.4f} | {eff[(name, spp)]:.4g} |")
            print(f"\n{name}: start-up and scene build {intercept:.2f} CPU s\n")
        print("celadon / Cycles efficiency: " +
              ", ".join(f"{spp} spp {eff[('celadon', spp)] / eff[('cycles', spp)]:.2f}" for spp in spps))
        sys.stdout.flush()


main()
