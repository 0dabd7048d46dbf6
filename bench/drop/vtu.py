"""Minimal reader of cufem's VTU (binary base64, UInt64 headers) without numpy."""
import base64, re, struct

FMT = {"Float64": "d", "Int32": "i", "Int64": "q", "UInt8": "B"}


def read(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)"(?: Name="(\w+)")? NumberOfComponents="(\d+)" format="binary">([^<]*)</DataArray>', text):
        typ, name, nc, data = m.group(1), m.group(2) or "Points", int(m.group(3)), m.group(4).strip()
        raw = base64.b64decode(data)
        n = struct.unpack("<Q", raw[:8])[0]
        f = FMT[typ]
        size = struct.calcsize(f)
        vals = struct.unpack("<%d%s" % (n // size, f), raw[8:8 + n])
        if nc > 1:
            vals = [vals[i:i + nc] for i in range(0, len(vals), nc)]
        out[name] = list(vals)
    return out


def interface_jumps(d, zs, tol=1e-9):
    """Per interface z: {(x, y): (jump vector above-below, s_zz mean, s_yz mean, d_interface or None)}."""
    pts, conn, off = d["Points"], d["connectivity"], d["offsets"]
    # each point's cell centroid z
    cz = [0.0] * len(pts)
    start = 0
    for end in off:
        ids = conn[start:end]
        zc = sum(pts[i][2] for i in ids) / len(ids)
        for i in ids:
            cz[i] = zc
        start = end
    res = {}
    for z in zs:
        below, above = {}, {}
        for i, p in enumerate(pts):
            if abs(p[2] - z) < tol:
                key = (round(p[0], 9), round(p[1], 9))
                (above if cz[i] > z else below).setdefault(key, []).append(i)
        rows = {}
        for key in sorted(set(below) & set(above), key=lambda k: (k[1], k[0])):
            ia, ib = above[key][0], below[key][0]
            jump = [d["displacement"][ia][c] - d["displacement"][ib][c] for c in range(3)]
            sel = above[key] + below[key]
            szz = sum(d["s_zz"][i] for i in sel) / len(sel)
            syz = sum(d["s_yz"][i] for i in sel) / len(sel)
            di = None
            if "d_interface" in d:
                di = max(d["d_interface"][i] for i in sel)
            rows[key] = (jump, szz, syz, di)
        res[z] = rows
    return res
