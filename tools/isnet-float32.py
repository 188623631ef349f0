#!/usr/bin/python3
"""ISNet's float16 ONNX graph -> float32 with only its first output, for
OpenCV's DNN module (which reads no float16 weights). A build step of
`make deps-model` (docs/algorithms-recon.md, "Learned object prior"):
    isnet-float32.py IN.onnx OUT.onnx SIDE
Every float16 tensor becomes float32 and every Cast an Identity (the graph
casts only between float16 and float32); the side outputs are dropped and
the nodes put in topological order (the package's are not, which OpenCV's
importer needs). The input becomes 1 x 3 x SIDE x SIDE (a multiple of 64,
the network's coarsest grid): every upsampling's target size is a constant
of the export at 1024, scaled here by SIDE / 1024."""
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

FLOAT16, FLOAT = TensorProto.FLOAT16, TensorProto.FLOAT


def to_float32(t):
    return numpy_helper.from_array(numpy_helper.to_array(t).astype(np.float32), t.name) if t.data_type == FLOAT16 else t


def topological(nodes, ready):
    ready, done, order = set(ready), [False] * len(nodes), []
    while len(order) < len(nodes):
        before = len(order)
        for i, n in enumerate(nodes):
            if not done[i] and all(x == "" or x in ready for x in n.input):
                done[i] = True
                order.append(n)
                ready.update(n.output)
        if len(order) == before:
            sys.exit("isnet-float32.py: the graph has a cycle or an unknown input")
    return order


def scale_resize_targets(g, side):
    made = {o: n for n in g.node for o in n.output}
    for n in g.node:
        if n.op_type != "Resize":
            continue
        for part in made[n.input[3]].input:  # sizes = Concat(N and C of the input, the target H W)
            c = made.get(part)
            if c is not None and c.op_type == "Constant":
                v = numpy_helper.to_array(c.attribute[0].t)
                if v.size == 2:
                    c.attribute[0].t.CopyFrom(numpy_helper.from_array(v * side // 1024, c.attribute[0].t.name))


def main(src, dst, side):
    if side % 64 or not 64 <= side <= 1024:
        sys.exit("isnet-float32.py: SIDE must be a multiple of 64 up to 1024")
    model = onnx.load(src)
    g = model.graph
    scale_resize_targets(g, side)
    for i, t in enumerate(g.initializer):
        g.initializer[i].CopyFrom(to_float32(t))
    for n in g.node:
        for a in n.attribute:
            if a.type == onnx.AttributeProto.TENSOR:
                a.t.CopyFrom(to_float32(a.t))
        if n.op_type == "Cast":
            n.CopyFrom(helper.make_node("Identity", list(n.input), list(n.output), name=n.name))
    for v in list(g.input) + list(g.output) + list(g.value_info):
        if v.type.tensor_type.elem_type == FLOAT16:
            v.type.tensor_type.elem_type = FLOAT
    del g.output[1:]
    for v in (g.input[0], g.output[0]):
        v.type.tensor_type.shape.dim[2].dim_value = side
        v.type.tensor_type.shape.dim[3].dim_value = side
    del g.value_info[:]
    order = topological(g.node, [v.name for v in g.input] + [t.name for t in g.initializer])
    del g.node[:]
    g.node.extend(order)
    onnx.checker.check_model(model)
    onnx.save(model, dst)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: isnet-float32.py IN.onnx OUT.onnx SIDE")
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
