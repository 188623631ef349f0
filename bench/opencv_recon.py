#!/usr/bin/env python3
"""OpenCV reference timings for the image stages of `celadon reconstruct`.

Times the OpenCV operations that do what bench_recon.c times, on the same
photo and cleaned mask (out/bench/bench_recon_{photo,mask}.png, written by
build/bench/bench_recon), median of 21 runs, OpenCV limited to one thread like
each celadon stage.
Used only by `make bench` (needs Debian's python3-opencv); never by tests.
"""
import statistics
import sys
import time

import cv2
import numpy as np

REPS = 21


def timed(label, fn):
    """Median wall and thread CPU time (the CPU time does not count the time
    other processes hold the shared cores)."""
    fn()  # warm-up
    wall, cpu = [], []
    for _ in range(REPS):
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


if __name__ == "__main__":
    main()
