#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_canvas (tests/fuzz/corpus/canvas/): short call sequences in its input format."""
import os
import sys

SPECIAL = {"nan": 0, "inf": 1, "-inf": 2, "1e300": 4, "-1e300": 5}


def num(v):
    if isinstance(v, str):
        return bytes([SPECIAL[v]])
    raw = int(round(v * 64)) + 30720
    return bytes([16 + (raw >> 8), raw & 255])


def call(op, *args, small=()):
    out = bytes([op])
    for a in args:
        out += num(a)
    return out + bytes(small)


# opcodes of fuzz_canvas.cpp
SAVE, RESTORE, TRANSLATE, SCALE, ROTATE = 0, 1, 2, 3, 4
MOVE, LINE, QUAD, CUBIC, ARC, RECT, ROUND_RECT, CLOSE, BEGIN = 7, 8, 9, 10, 11, 14, 15, 16, 17
FILL, STROKE, CLIP, FILL_RECT, FILL_RGBA, STROKE_RGBA, NEW_PAINT, USE_PAINT = 18, 19, 20, 21, 24, 25, 26, 28
LINE_WIDTH, DASH, ALPHA, COMPOSITE, AA, LAYER, LAYER_MASKED, END_LAYER, DRAW_IMAGE, SHADOW = (
    29, 33, 34, 35, 36, 37, 38, 39, 40, 44)

seeds = {
    "fill_rules": bytes([48]) + call(BEGIN) + call(RECT, 4, 4, 30, 30) + call(RECT, 14, 14, 30, 30)
    + call(FILL, small=[1]) + call(AA, small=[2]) + call(FILL, small=[2]),
    "gradient_clip": bytes([40]) + call(BEGIN) + call(ARC, 20, 20, 15, 0, 6.28, small=[0]) + call(CLIP, small=[0])
    + call(NEW_PAINT, small=[0]) + num(0) + num(0) + num(5) + num(40) + num(40)
    + bytes([2]) + num(0) + num(1) + num(0) + num(0) + num(1) + num(1) + num(0) + num(0) + num(1) + num(1)
    + bytes([1, 0]) + bytes([1]) + call(USE_PAINT, small=[1]) + call(FILL_RECT, 0, 0, 40, 40),
    "layer_stroke": bytes([32]) + call(LAYER, 0.5) + call(FILL_RGBA, 1, 0, 0, 1) + call(FILL_RECT, 2, 2, 20, 20)
    + call(LINE_WIDTH, 3) + call(BEGIN) + call(MOVE, 0, 0) + call(CUBIC, 10, 30, 20, -5, 31, 31) + call(STROKE)
    + call(END_LAYER) + call(COMPOSITE, small=[12]) + call(FILL_RECT, 8, 8, 8, 8),
    "bad_numbers": bytes([16]) + call(TRANSLATE, "nan", 1) + call(SCALE, "inf", 2) + call(BEGIN)
    + call(MOVE, "1e300", "-1e300") + call(LINE, 8, "nan") + call(ARC, 8, 8, "inf", 0, 3, small=[1])
    + call(FILL, small=[0]) + call(FILL_RECT, "-inf", 0, 4, 4) + call(DASH, small=[2]) + num(1) + num("nan") + num(0)
    + call(STROKE) + call(END_LAYER) + call(RESTORE),
    "shadow_image": bytes([24]) + call(SHADOW, 0, 0, 0, 0.5, 2, 2, 3) + call(FILL_RGBA, 0, 0, 1, 1)
    + call(FILL_RECT, 4, 4, 8, 8) + call(DRAW_IMAGE, 2, 2, 9, 6, small=[1])
    + call(LAYER_MASKED, 1, small=[0, 9, 9, 1, 1]) + call(FILL_RECT, 0, 0, 24, 24) + call(END_LAYER),
}

out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus", "canvas")
os.makedirs(out_dir, exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join(out_dir, name), "wb") as f:
        f.write(data)
