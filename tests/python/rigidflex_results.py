"""Readers for RigidFlex result files, written from the published formats only (no RigidFlex code):

- the LS-DYNA binary d3plot database (LS-DYNA manual, "LS-DYNA Database Binary Output Files":
  64 control words, material types, geometry, user IDs, then states up to the -999999.0 marker),
- VTK XML UnstructuredGrid files with appended raw data (VTK file-format documentation),
- the .pvd collection and the CSV files.

Standard library only (struct, xml.etree), so the checks run wherever python3 does.
"""
import csv
import os
import re
import struct
import xml.etree.ElementTree as ET

EOF_MARKER = -999999.0


def _family(path):
    """d3plot, d3plot01, d3plot02, ... in order."""
    files = [path]
    k = 1
    while os.path.exists("%s%02d" % (path, k)):
        files.append("%s%02d" % (path, k))
        k += 1
    return files


class D3plot:
    def __init__(self, path):
        members = [open(f, "rb").read() for f in _family(path)]
        first = members[0]
        assert len(first) % 4 == 0, "d3plot: size is not a whole number of 4-byte words"
        version = struct.unpack_from("<f", first, 14 * 4)[0]
        assert 900.0 < version < 1000.0, "d3plot: version word %r, not a 4-byte little-endian file" % version
        self.title = first[:40].decode("ascii").rstrip()
        c = struct.unpack_from("<64i", first, 0)
        self.control = c
        self.ndim, self.numnp, self.icode, self.nglbv = c[15], c[16], c[17], c[18]
        self.it, self.iu, self.iv, self.ia = c[19], c[20], c[21], c[22]
        self.nel8, self.nummat8, self.nv3d = c[23], c[24], c[27]
        self.nel2, self.nummat2, self.nv1d = c[28], c[29], c[30]
        self.nel4, self.nummat4, self.nv2d = c[31], c[32], c[33]
        self.neiph, self.neips, self.nelt = c[34], c[35], c[40]
        self.maxint, self.narbs, self.nmmat = c[36], c[39], c[51]
        self.ioshl = [1 if c[k] == 1000 else 0 for k in range(43, 47)]
        assert self.ndim in (4, 5), "NDIM %d" % self.ndim
        assert self.nelt == 0, "thick shells not expected"
        # Shell points written: |MAXINT| - 10000 when element deletion flags follow.
        self.shell_points = -self.maxint - 10000 if self.maxint < -10000 else abs(self.maxint)
        if self.nel4:
            expected = (self.shell_points * (6 * self.ioshl[0] + self.ioshl[1] + self.neips)
                        + 8 * self.ioshl[2] + 4 * self.ioshl[3])
            assert self.nv2d == expected, "NV2D %d, the flags give %d (strains not expected)" % (self.nv2d, expected)
        pos = 64
        words = lambda fmt, n: struct.unpack_from("<%d%s" % (n, fmt), first, 4 * pos)
        self.material_types = []
        if self.ndim == 5:
            numrbe, nummat = words("i", 2)
            pos += 2
            self.material_types = list(words("i", nummat))
            pos += nummat
        xyz = words("f", 3 * self.numnp)
        self.x0 = [xyz[3 * i:3 * i + 3] for i in range(self.numnp)]
        pos += 3 * self.numnp
        conn = words("i", 9 * self.nel8)
        self.solids = [conn[9 * e:9 * e + 8] for e in range(self.nel8)]  # 1-based node numbers
        self.solid_material = [conn[9 * e + 8] for e in range(self.nel8)]
        pos += 9 * self.nel8
        # Geometry continues with thick shells (none), beams (N1 N2 N3 NS1 NS2 MAT) and shells
        # (N1 N2 N3 N4 MAT).
        conn = words("i", 6 * self.nel2)
        self.beams = [conn[6 * e:6 * e + 5] for e in range(self.nel2)]
        self.beam_material = [conn[6 * e + 5] for e in range(self.nel2)]
        pos += 6 * self.nel2
        conn = words("i", 5 * self.nel4)
        self.shells = [conn[5 * e:5 * e + 4] for e in range(self.nel4)]
        self.shell_material = [conn[5 * e + 4] for e in range(self.nel4)]
        pos += 5 * self.nel4
        self.beam_ids = list(range(1, self.nel2 + 1))
        self.shell_ids = list(range(1, self.nel4 + 1))
        self.node_ids = list(range(1, self.numnp + 1))
        self.solid_ids = list(range(1, self.nel8 + 1))
        self.part_ids = list(range(1, self.nmmat + 1))
        if self.narbs > 0:
            start = pos
            head = words("i", 10)
            pos += 10
            nsort = head[0]
            if nsort < 0:
                pos += 6
            self.node_ids = list(words("i", self.numnp))
            pos += self.numnp
            self.solid_ids = list(words("i", self.nel8))
            pos += self.nel8
            # Element IDs: solids, beams (pointer NSRB), shells (NSRS), thick shells (NSRT);
            # the pointers are word addresses in the file.
            assert head[2] == pos and head[7] == self.nel2, "NSRB %d / NSRBD %d" % (head[2], head[7])
            self.beam_ids = list(words("i", self.nel2))
            pos += self.nel2
            assert head[3] == pos and head[8] == self.nel4, "NSRS %d / NSRSD %d" % (head[3], head[8])
            self.shell_ids = list(words("i", self.nel4))
            pos += self.nel4
            if nsort < 0:
                self.part_ids = list(words("i", self.nmmat))  # ordered user IDs
                pos += 3 * self.nmmat
            assert pos - start == self.narbs, "NARBS %d, user-ID section %d words" % (self.narbs, pos - start)
        self.deletion = self.maxint < -10000
        self.state_words = (1 + self.nglbv + (self.it + 3 * (self.iu + self.iv + self.ia)) * self.numnp
                            + self.nv3d * self.nel8 + self.nv1d * self.nel2 + self.nv2d * self.nel4
                            + ((self.nel8 + self.nel4 + self.nel2) if self.deletion else 0))
        self.states = []
        self.part_titles = {}
        blobs = [(first, 4 * pos)] + [(m, 0) for m in members[1:]]
        for blob, at in blobs:
            while True:
                assert at + 4 <= len(blob), "d3plot member ends without the end-of-file marker"
                t = struct.unpack_from("<f", blob, at)[0]
                if t == EOF_MARKER and blob is first and at + 4 < len(blob):
                    at = self._titles(blob, at + 4)
                    continue
                if t == EOF_MARKER:
                    assert at + 4 == len(blob), "data after the end-of-file marker"
                    break
                assert at + 4 * self.state_words <= len(blob), "d3plot: a state is cut short"
                self.states.append(self._state(blob, at))
                at += 4 * self.state_words

    def _titles(self, blob, at):
        """The title section after the geometry (NTYPE 90001: NUMPROP, then per part its ID and
        72 characters); returns where it ends."""
        ntype, numprop = struct.unpack_from("<2i", blob, at)
        assert ntype == 90001, "d3plot: title section of type %d, expected 90001" % ntype
        at += 8
        for _ in range(numprop):
            pid = struct.unpack_from("<i", blob, at)[0]
            self.part_titles[pid] = blob[at + 4:at + 76].decode("ascii").rstrip()
            at += 76
        return at

    def _state(self, blob, at):
        v = struct.unpack_from("<%df" % self.state_words, blob, at)
        s = {"time": v[0], "globals": v[1:1 + self.nglbv]}
        p = 1 + self.nglbv + self.it * self.numnp
        for name, flag in (("coordinates", self.iu), ("velocity", self.iv), ("acceleration", self.ia)):
            if flag:
                s[name] = [v[p + 3 * i:p + 3 * i + 3] for i in range(self.numnp)]
                p += 3 * self.numnp
        s["solid"] = [v[p + self.nv3d * e:p + self.nv3d * (e + 1)] for e in range(self.nel8)]
        p += self.nv3d * self.nel8
        s["beam"] = [v[p + self.nv1d * e:p + self.nv1d * (e + 1)] for e in range(self.nel2)]
        p += self.nv1d * self.nel2
        s["shell"] = [v[p + self.nv2d * e:p + self.nv2d * (e + 1)] for e in range(self.nel4)]
        p += self.nv2d * self.nel4
        if self.deletion:
            # Deletion flags in the format's order: solids, thick shells, shells, beams.
            s["alive"] = list(v[p:p + self.nel8])
            p += self.nel8
            s["shell_alive"] = list(v[p:p + self.nel4])
            p += self.nel4
            s["beam_alive"] = list(v[p:p + self.nel2])
        return s


_TYPES = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B", "UInt64": "Q"}


def read_vtu(path):
    """{'points', 'point_data', 'cell_data', 'field_data', 'connectivity', 'offsets', 'types'}."""
    raw = open(path, "rb").read()
    marker = raw.index(b"<AppendedData")
    underscore = raw.index(b"_", marker)
    xml_text = raw[:marker].decode() + "</VTKFile>"
    root = ET.fromstring(xml_text)
    assert root.get("header_type") == "UInt64" and root.get("byte_order") == "LittleEndian"
    data = raw[underscore + 1:]

    def array(a):
        offset = int(a.get("offset"))
        nbytes = struct.unpack_from("<Q", data, offset)[0]
        code = _TYPES[a.get("type")]
        count = nbytes // struct.calcsize(code)
        values = struct.unpack_from("<%d%s" % (count, code), data, offset + 8)
        k = int(a.get("NumberOfComponents", "1"))
        return [values[i:i + k] for i in range(0, count, k)] if k > 1 else list(values)

    out = {"point_data": {}, "cell_data": {}, "field_data": {}}
    for a in root.iter("DataArray"):
        pass
    grid = root.find("UnstructuredGrid")
    for a in grid.find("FieldData") or []:
        out["field_data"][a.get("Name")] = array(a)
    piece = grid.find("Piece")
    out["points"] = array(piece.find("Points").find("DataArray"))
    for a in piece.find("PointData"):
        out["point_data"][a.get("Name")] = array(a)
    for a in piece.find("CellData"):
        out["cell_data"][a.get("Name")] = array(a)
    for a in piece.find("Cells"):
        out[a.get("Name")] = array(a)
    return out


def read_pvd(path):
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def support_impulse(out, glstat):
    """Impulse of the support reactions over a run whose spcforc.csv has a row per constrained
    node and cycle, summed with glstat's steps: the rows of one time are summed; the row at t^n is
    the step's reaction, m (v^{n+1/2} - v^{n-1/2}) / dt_avg - f, and glstat's momentum at t^n is
    taken with v^{n+1/2}, so sum_n dt_avg^n R^n (n >= 1) is the momentum change the supports
    caused. Returns (impulse [x, y, z], whether spcforc has exactly glstat's times)."""
    spc = {}
    for r in read_csv(os.path.join(out, "spcforc.csv")):
        s = spc.setdefault(r["time"], [0.0, 0.0, 0.0])
        for d, c in enumerate(("force_x", "force_y", "force_z")):
            s[d] += r[c]
    times = [r["time"] for r in glstat]
    dts = [r["dt"] for r in glstat]
    impulse = [0.0, 0.0, 0.0]
    for n in range(1, len(glstat)):
        dt_avg = 0.5 * (dts[n - 1] + dts[n])
        for d in range(3):
            impulse[d] += dt_avg * spc.get(times[n], (0.0, 0.0, 0.0))[d]
    return impulse, len(spc) == len(glstat) and sorted(spc) == times
