#!/usr/bin/env python3
"""OpenCV reference timings for the image stages of `celadon reconstruct`.

Times the OpenCV operations that do what bench_recon.c times, on the same
photo and cleaned mask (out/bench/bench_recon_{photo,mask}.png, written by
build/bench/bench_recon), median of 21 runs, OpenCV limited to one thread like
each celadon stage; then GrabCut, the standard tool for what celadon's
segmentation does, on the same photo.
Used only by `make bench` (needs Debian's python3-opencv); never by tests.
"""
import statistics
import sys
import time

import cv2
import numpy as np

REPS = 21


def timed(label, fn, reps=REPS):
    """Median wall and thread CPU time (the CPU time does not count the time
    other processes hold the shared cores)."""
    fn()  # warm-up
    wall, cpu = [], []
    for _ in range(reps):
        t0, c0 = time.perf_counter(), time.thread_time()
        out = fn()
        wall.append(1e3 * (time.perf_counter() - t0))
        cpu.append(1e3 * (time.thread_time() - c0))
    print(f"  {label:<44} {statistics.median(wall):9.3f} {statistics.median(cpu):9.3f}")
    return out


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "out/bench/bench_recon_photo.png"
    mask_path = sys.argv[2] if len(sys.argv) > 2 else "out/bench/bench_recon_mask.png"
    cv2.setNumThreads(1)
    print(f"OpenCV {cv2.__version__} reference on {path}, 1 thread, median of {REPS} runs")
    print(f"  {'stage':<44} {'wall ms':>9} {'CPU ms':>9}")
    img = timed("decode (cv2.imread)", lambda: cv2.imread(path, cv2.IMREAD_COLOR))
    gray = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    timed("mask (gray + Otsu threshold only)",
          lambda: cv2.threshold(cv2.cvtColor(img, cv2.COLOR_BGR2GRAY), 0, 1,
                                cv2.THRESH_BINARY_INV | cv2.THRESH_OTSU)[1])
    # celadon's decoder hands the recon float pixels (image_t); the gray
    # conversion alone from such an image, for comparison.
    imgf = img.astype(np.float32) / 255
    timed("  gray from float32 RGB only (cvtColor)", lambda: cv2.cvtColor(imgf, cv2.COLOR_BGR2GRAY))
    # The later stages run on celadon's cleaned mask, so both trace the same outline.
    mask = (cv2.imread(mask_path, cv2.IMREAD_GRAYSCALE) > 127).astype(np.uint8)
    contours = timed("contour (findContours, external, no approx)",
                     lambda: cv2.findContours(mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)[0])
    contour = max(contours, key=len)
    timed("Douglas-Peucker (approxPolyDP, eps 1 px)", lambda: cv2.approxPolyDP(contour, 1.0, True))
    maskf = mask.astype(np.float32)
    blur = timed("Gaussian 7x7 sigma 1.4 (GaussianBlur)", lambda: cv2.GaussianBlur(maskf, (7, 7), 1.4))
    timed("Shi-Tomasi response (cornerMinEigenVal)", lambda: cv2.cornerMinEigenVal(blur, 3, 3))
    timed("Shi-Tomasi corners (goodFeaturesToTrack)",
          lambda: cv2.goodFeaturesToTrack(blur, 20, 0.01, 10, blockSize=3))
    pts = contour.reshape(-1, 2).astype(np.float64)
    timed("PCA of the contour (PCACompute2)", lambda: cv2.PCACompute2(pts, mean=None))
    print(f"  ({len(contour)} contour points; gray {gray.shape[1]}x{gray.shape[0]})")
    grabcut(img)


GRABCUT_REPS = 5


def grabcut(img):
    """GrabCut (5-component mixtures and a min-cut, like celadon's
    segmentation without its backdrop surface, shadow and symmetry terms),
    3 iterations from a rectangle 6% inside the border (celadon's border ring
    is its backdrop prior): on the whole photo, and on the photo box-filtered
    to celadon's working resolution (longer side ~200 px, as recon_segment
    does before refining a band around the outline at full resolution)."""
    h, w = img.shape[:2]
    print(f"GrabCut (cv2.grabCut, 3 iterations, rectangle 6% inside the border), median of {GRABCUT_REPS} runs")
    print(f"  {'stage':<44} {'wall ms':>9} {'CPU ms':>9}")
    f = max(1, round(max(w, h) / 200))
    small = cv2.resize(img, (w // f, h // f), interpolation=cv2.INTER_AREA)
    for label, im in ((f"whole photo {w}x{h}", img), (f"box-filtered to {w // f}x{h // f}", small)):
        ih, iw = im.shape[:2]
        rect = (int(0.06 * iw), int(0.06 * ih), iw - 2 * int(0.06 * iw), ih - 2 * int(0.06 * ih))

        def run():
            mask = np.zeros((ih, iw), np.uint8)
            bgd, fgd = np.zeros((1, 65), np.float64), np.zeros((1, 65), np.float64)
            cv2.grabCut(im, mask, rect, bgd, fgd, 3, cv2.GC_INIT_WITH_RECT)
            return mask

        timed(f"GrabCut, {label}", run, GRABCUT_REPS)


if __name__ == "__main__":
    main()
