#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""npy_check.py TABLE.npy TABLE.csv: the .npy table of `hystviz sweep --table
npy` holds the CSV table's values bit for bit (docs/STUDIES.md): the same
column names in order, index and status (0 ok, 1 invalid, 2 failed), the
texts (name, text grid values, message: the CSV's bytes, NUL-padded, the
message cut at 256 bytes), and every number the double its CSV text reads
as (float64 bits equal; NaN where the CSV is empty); minor_areas the first
8 of the CSV's ';'-list, NaN after.  Prints the count checked; exit 1 on a
difference, naming the first."""
import csv
import math
import struct
import sys

import numpy as np

a = np.load(sys.argv[1])
with open(sys.argv[2], newline="") as f:
    rows = list(csv.reader(f))
head, rows = rows[0], rows[1:]
names = list(a.dtype.names)
assert names == head, (names, head)
assert a.shape == (len(rows),), (a.shape, len(rows))
bits = lambda x: struct.pack("<d", x)
st = {"ok": 0, "invalid": 1, "failed": 2}
n = 0
for i, r in enumerate(rows):
    rec = a[i]
    for c, text in zip(names, r):
        v = rec[c]
        kind = a.dtype[c].kind
        if c == "index":
            ok = int(v) == int(text)
        elif c == "status":
            ok = int(v) == st[text]
        elif kind == "S":
            want = text.encode()
            if c == "message" and len(want) > 256:
                want = want[:256]
                while want and (want[-1] & 0xC0) == 0x80:
                    want = want[:-1]
            ok = bytes(v) == want
        elif c == "minor_areas":
            parts = [float(t) for t in text.split(";")] if text else []
            ok = all(bits(float(v[k])) == bits(parts[k]) if k < len(parts) else math.isnan(v[k]) for k in range(8))
        else:
            ok = math.isnan(v) if text == "" else bits(float(v)) == bits(float(text))
        if not ok:
            print(f"npy_check: row {i} column {c}: npy {v!r}, csv {text!r}")
            sys.exit(1)
        n += 1
print(f"npy_check: {len(rows)} rows, {n} fields equal to the CSV's bit for bit")
