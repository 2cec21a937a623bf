#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Test volumes written at test time: an asymmetric phantom in every format, and DICOM series of every kind.

  volumes.py orient DIR   the phantom (an L-shaped marker and a sphere, distinct along each axis) written in
                          NRRD, NIfTI-1 (sform, qform), NIfTI-2, MetaImage (.mhd, .mha, TransformMatrix or
                          AnatomicalOrientation) and DICOM, each with its own order and signs of the axes; DIR/list
                          names one file a line. Read in the patient frame, every one is the same volume as
                          DIR/reference.nrrd.
  volumes.py dicom DIR    DICOM series for tests/port/dicom.sh: 8- and 16-bit, signed with rescale, unsorted file
                          names, a missing slice, two series in one folder, a gantry tilt, a multi-frame file, a
                          series of 120 slices; DIR/ANY/NAME.dcm.

Only the standard library and pydicom (Debian's python3-pydicom; no numpy): the volumes are small.
"""
import math
import os
import random
import struct
import sys
import zlib

# The phantom in the patient frame LPS: x towards the left, y posterior, z superior. Distinct sizes and spacings
# along the three axes, so that an axis taken for another changes the volume.
DIMS = (24, 20, 16)
SPACING = (1.0, 1.25, 1.5)


def phantom():
    """Values indexed [z][y][x]: a sphere (120) on the right, an L-shaped marker (240) on the left, low and in front,
    its long arm along x, its upright arm along z and a nub along y."""
    nx, ny, nz = DIMS
    v = [[[0] * nx for _ in range(ny)] for _ in range(nz)]
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                if (x - 6) ** 2 + (y - 12) ** 2 + (z - 9) ** 2 <= 16:
                    v[z][y][x] = 120
                if 3 <= y <= 5 and 3 <= z <= 5 and 13 <= x <= 21:
                    v[z][y][x] = 240
                if 3 <= y <= 5 and 3 <= z <= 13 and 13 <= x <= 15:
                    v[z][y][x] = 240
                if 3 <= y <= 9 and 3 <= z <= 5 and 19 <= x <= 21:
                    v[z][y][x] = 240
    return v


def stored(v, perm, sign):
    """The phantom as a file stores it: stored axis c is patient axis perm[c], reversed when sign[c] < 0. Returns the
    stored dims and the values, x fastest."""
    dims = [DIMS[perm[c]] for c in range(3)]
    out = []
    for k in range(dims[2]):
        for j in range(dims[1]):
            for i in range(dims[0]):
                p = [0, 0, 0]
                for c, idx in enumerate((i, j, k)):
                    p[perm[c]] = idx if sign[c] > 0 else DIMS[perm[c]] - 1 - idx
                out.append(v[p[2]][p[1]][p[0]])
    return dims, out


def axes_lps(perm, sign):
    """Each stored axis's LPS vector, spacing long."""
    axes = []
    for c in range(3):
        a = [0.0, 0.0, 0.0]
        a[perm[c]] = sign[c] * SPACING[perm[c]]
        axes.append(a)
    return axes


def pack(values, fmt):
    return struct.pack("<%d%s" % (len(values), fmt), *values)


def write_nrrd(path, perm, sign, space="left-posterior-superior", encoding="raw"):
    dims, vals = stored(phantom(), perm, sign)
    axes = axes_lps(perm, sign)
    if space == "right-anterior-superior":
        axes = [[-a[0], -a[1], a[2]] for a in axes]
    head = "NRRD0004\ntype: uint8\ndimension: 3\nspace: %s\nsizes: %d %d %d\n" % (space, *dims)
    head += "space directions: %s\n" % " ".join("(%g,%g,%g)" % tuple(a) for a in axes)
    head += "space origin: (10,-20,30)\nencoding: %s\n\n" % encoding
    if encoding == "raw":
        data = bytes(vals)
    elif encoding == "gzip":
        c = zlib.compressobj(9, zlib.DEFLATED, 31)
        data = c.compress(bytes(vals)) + c.flush()
    elif encoding == "ascii":
        data = "\n".join(" ".join(str(x) for x in vals[r:r + dims[0]]) for r in range(0, len(vals), dims[0])).encode()
    else:  # hex
        data = "\n".join(bytes(vals[r:r + 32]).hex() for r in range(0, len(vals), 32)).encode()
    with open(path, "wb") as f:
        f.write(head.encode() + data)


def quaternion(m):
    """nifti_mat44_to_quatern for a rotation-or-reflection with unit columns: (b, c, d, qfac)."""
    r = [row[:] for row in m]
    det = (r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
           r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]))
    qfac = 1.0
    if det < 0:
        qfac = -1.0
        for i in range(3):
            r[i][2] = -r[i][2]
    a = r[0][0] + r[1][1] + r[2][2] + 1
    if a > 0.5:
        a = 0.5 * math.sqrt(a)
        b = 0.25 * (r[2][1] - r[1][2]) / a
        c = 0.25 * (r[0][2] - r[2][0]) / a
        d = 0.25 * (r[1][0] - r[0][1]) / a
    else:
        xd = 1.0 + r[0][0] - (r[1][1] + r[2][2])
        yd = 1.0 + r[1][1] - (r[0][0] + r[2][2])
        zd = 1.0 + r[2][2] - (r[0][0] + r[1][1])
        if xd > 1.0:
            b = 0.5 * math.sqrt(xd)
            c = 0.25 * (r[0][1] + r[1][0]) / b
            d = 0.25 * (r[0][2] + r[2][0]) / b
            a = 0.25 * (r[2][1] - r[1][2]) / b
        elif yd > 1.0:
            c = 0.5 * math.sqrt(yd)
            b = 0.25 * (r[0][1] + r[1][0]) / c
            d = 0.25 * (r[1][2] + r[2][1]) / c
            a = 0.25 * (r[0][2] - r[2][0]) / c
        else:
            d = 0.5 * math.sqrt(zd)
            b = 0.25 * (r[0][2] + r[2][0]) / d
            c = 0.25 * (r[1][2] + r[2][1]) / d
            a = 0.25 * (r[1][0] - r[0][1]) / d
        if a < 0:
            b, c, d = -b, -c, -d
    return b, c, d, qfac


def write_nifti(path, perm, sign, version=1, form="sform", datatype=2):
    dims, vals = stored(phantom(), perm, sign)
    ras = [[-a[0], -a[1], a[2]] for a in axes_lps(perm, sign)]  # NIfTI's world is RAS
    spacing = [SPACING[perm[c]] for c in range(3)]
    unit = [[ras[c][r] / spacing[c] for c in range(3)] for r in range(3)]  # columns: axes
    b, c, d, qfac = quaternion(unit)
    data = bytes(vals) if datatype == 2 else pack([x * 10 - 500 for x in vals], "h")
    if version == 1:
        h = bytearray(352)
        struct.pack_into("<i", h, 0, 348)
        struct.pack_into("<8h", h, 40, 3, *dims, 1, 1, 1, 1)
        struct.pack_into("<hh", h, 70, datatype, 8 if datatype == 2 else 16)
        struct.pack_into("<8f", h, 76, qfac, *spacing, 1, 1, 1, 1)
        struct.pack_into("<f", h, 108, 352)
        struct.pack_into("<ff", h, 112, 0.1 if datatype == 4 else 0, 50 if datatype == 4 else 0)
        struct.pack_into("<hh", h, 252, 1 if form == "qform" else 0, 1 if form == "sform" else 0)
        struct.pack_into("<6f", h, 256, b, c, d, 10, -20, 30)
        for r in range(3):
            struct.pack_into("<4f", h, 280 + 16 * r, *[ras[a][r] for a in range(3)], 0)
        h[344:348] = b"n+1\0"
    else:
        h = bytearray(544)
        struct.pack_into("<i", h, 0, 540)
        h[4:12] = b"n+2\0\r\n\x1a\n"
        struct.pack_into("<hh", h, 12, datatype, 8 if datatype == 2 else 16)
        struct.pack_into("<8q", h, 16, 3, *dims, 1, 1, 1, 1)
        struct.pack_into("<8d", h, 104, qfac, *spacing, 1, 1, 1, 1)
        struct.pack_into("<q", h, 168, 544)
        struct.pack_into("<dd", h, 176, 0.1 if datatype == 4 else 0, 50 if datatype == 4 else 0)
        struct.pack_into("<ii", h, 344, 1 if form == "qform" else 0, 1 if form == "sform" else 0)
        struct.pack_into("<6d", h, 352, b, c, d, 10, -20, 30)
        for r in range(3):
            struct.pack_into("<4d", h, 400 + 32 * r, *[ras[a][r] for a in range(3)], 0)
    with open(path, "wb") as f:
        f.write(bytes(h) + data)


def write_metaimage(path, perm, sign, local=False, compressed=False, anatomical_only=False, big=False):
    dims, vals = stored(phantom(), perm, sign)
    axes = axes_lps(perm, sign)
    spacing = [SPACING[perm[c]] for c in range(3)]
    lines = ["ObjectType = Image", "NDims = 3", "BinaryData = True",
             "BinaryDataByteOrderMSB = %s" % ("True" if big else "False")]
    if compressed:
        lines.append("CompressedData = True")
    if not anatomical_only:
        lines.append("TransformMatrix = " + " ".join("%g" % (axes[a][k] / spacing[a]) for a in range(3)
                                                     for k in range(3)))
    lines.append("Offset = 10 -20 30")
    lines.append("CenterOfRotation = 0 0 0")
    # ITK's letters: the side each axis comes from (RAI is the identity)
    letters = ""
    for a in range(3):
        k = perm[a]
        letters += ("RL", "AP", "IS")[k][0 if sign[a] > 0 else 1]
    lines.append("AnatomicalOrientation = " + letters)
    lines.append("ElementSpacing = %g %g %g" % tuple(spacing))
    lines.append("DimSize = %d %d %d" % tuple(dims))
    lines.append("ElementType = MET_SHORT" if big else "ElementType = MET_UCHAR")
    data = struct.pack(">%dh" % len(vals), *vals) if big else bytes(vals)
    if compressed:
        data = zlib.compress(data)
        lines.append("CompressedDataSize = %d" % len(data))
    if local:
        lines.append("ElementDataFile = LOCAL")
        with open(path, "wb") as f:
            f.write(("\n".join(lines) + "\n").encode() + data)
    else:
        raw = os.path.splitext(os.path.basename(path))[0] + (".zraw" if compressed else ".raw")
        lines.append("ElementDataFile = " + raw)
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        with open(os.path.join(os.path.dirname(path), raw), "wb") as f:
            f.write(data)


def dicom_series(folder, slices, rows, cols, iop, positions, spacing, bits=16, signed=True, slope=1.0, inter=0.0,
                 uid=None, description="test series", names=None, study=None, instance_base=1):
    """One file per slice; slices[k] is the list of rows*cols values of slice k."""
    import pydicom
    from pydicom.dataset import FileDataset, FileMetaDataset
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid

    os.makedirs(folder, exist_ok=True)
    uid = uid or generate_uid()
    study = study or generate_uid()
    frame = generate_uid()
    files = []
    for k, values in enumerate(slices):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"  # CT Image Storage
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        name = names[k] if names else "slice%03d.dcm" % k
        path = os.path.join(folder, name)
        ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
        ds.is_little_endian = True
        ds.is_implicit_VR = False
        ds.SOPClassUID = meta.MediaStorageSOPClassUID
        ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
        ds.Modality = "CT"
        ds.PatientName = "Phantom^Test"
        ds.PatientID = "0"
        ds.StudyInstanceUID = study
        ds.SeriesInstanceUID = uid
        ds.FrameOfReferenceUID = frame
        ds.SeriesDescription = description
        ds.InstanceNumber = instance_base + k
        ds.ImagePositionPatient = ["%.6g" % p for p in positions[k]]
        ds.ImageOrientationPatient = ["%.6g" % c for c in iop]
        ds.PixelSpacing = ["%.6g" % spacing[1], "%.6g" % spacing[0]]  # rows apart, columns apart
        ds.SliceThickness = "%.6g" % spacing[2]
        ds.Rows = rows
        ds.Columns = cols
        ds.SamplesPerPixel = 1
        ds.PhotometricInterpretation = "MONOCHROME2"
        ds.BitsAllocated = bits
        ds.BitsStored = bits if bits == 8 else 12
        ds.HighBit = ds.BitsStored - 1
        ds.PixelRepresentation = 1 if signed else 0
        if slope != 1.0 or inter != 0.0:
            ds.RescaleSlope = "%.6g" % slope
            ds.RescaleIntercept = "%.6g" % inter
            ds.RescaleType = "HU"
        fmt = ("b" if signed else "B") if bits == 8 else ("h" if signed else "H")
        ds.PixelData = struct.pack("<%d%s" % (len(values), fmt), *values)
        ds.save_as(path, write_like_original=False)
        files.append(path)
    return files


def enhanced_ct(path, slices, rows, cols, iop, positions, spacing, slope, inter, frame_order):
    """One Enhanced CT file holding every slice as a frame, the frames stored in frame_order; positions, orientation,
    spacing and rescale in the functional groups, as scanners write them."""
    from pydicom.dataset import Dataset, FileDataset, FileMetaDataset
    from pydicom.sequence import Sequence
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid

    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2.1"  # Enhanced CT Image Storage
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.is_little_endian = True
    ds.is_implicit_VR = False
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = "CT"
    ds.StudyInstanceUID = generate_uid()
    ds.SeriesInstanceUID = generate_uid()
    ds.FrameOfReferenceUID = generate_uid()
    ds.SeriesDescription = "enhanced CT"
    ds.Rows = rows
    ds.Columns = cols
    ds.NumberOfFrames = len(slices)
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated = 16
    ds.BitsStored = 12
    ds.HighBit = 11
    ds.PixelRepresentation = 1
    shared = Dataset()
    measures = Dataset()
    measures.PixelSpacing = ["%.6g" % spacing[1], "%.6g" % spacing[0]]
    measures.SliceThickness = "%.6g" % spacing[2]
    shared.PixelMeasuresSequence = Sequence([measures])
    orient = Dataset()
    orient.ImageOrientationPatient = ["%.6g" % c for c in iop]
    shared.PlaneOrientationSequence = Sequence([orient])
    rescale = Dataset()
    rescale.RescaleSlope = "%.6g" % slope
    rescale.RescaleIntercept = "%.6g" % inter
    rescale.RescaleType = "HU"
    shared.PixelValueTransformationSequence = Sequence([rescale])
    ds.SharedFunctionalGroupsSequence = Sequence([shared])
    frames = []
    for k in frame_order:
        item = Dataset()
        pos = Dataset()
        pos.ImagePositionPatient = ["%.6g" % p for p in positions[k]]
        item.PlanePositionSequence = Sequence([pos])
        frames.append(item)
    ds.PerFrameFunctionalGroupsSequence = Sequence(frames)
    data = []
    for k in frame_order:
        data.extend(slices[k])
    ds.PixelData = struct.pack("<%dh" % len(data), *data)
    ds.save_as(path, write_like_original=False)


def write_reference_nrrd(path, slices, rows, cols, spacing, type_name, fmt, directions=None):
    """The slices as the reader should see them: a column, a row and a slice along NRRD's axes 0, 1, 2, with no space
    (stored as they are, for series stacked along x, y, z) or in LPS along the directions given: for comparing
    hashes."""
    data = []
    for values in slices:
        data.extend(values)
    if directions:
        where = "space: left-posterior-superior\nspace directions: %s\n" % " ".join(
            "(%g,%g,%g)" % tuple(d * spacing[a] for d in directions[a]) for a in range(3))
    else:
        where = "spacings: %g %g %g\n" % tuple(spacing)
    with open(path, "wb") as f:
        f.write(("NRRD0004\ntype: %s\ndimension: 3\nsizes: %d %d %d\n%sendian: little\n"
                 "encoding: raw\n\n" % (type_name, cols, rows, len(slices), where)).encode())
        f.write(struct.pack("<%d%s" % (len(data), fmt), *data))


def phantom_dicom(folder, perm, sign, names_shuffled=True):
    """The phantom as DICOM slices: columns along stored axis 0, rows along 1, slices along 2."""
    dims, vals = stored(phantom(), perm, sign)
    axes = axes_lps(perm, sign)
    unit = [[x / SPACING[perm[c]] for x in axes[c]] for c in range(3)]
    origin = [10.0, -20.0, 30.0]
    n = dims[0] * dims[1]
    slices = [vals[k * n:(k + 1) * n] for k in range(dims[2])]
    positions = [[origin[i] + k * axes[2][i] for i in range(3)] for k in range(dims[2])]
    names = ["img%03d.dcm" % k for k in range(dims[2])]
    if names_shuffled:
        random.Random(7).shuffle(names)
    return dicom_series(folder, slices, dims[1], dims[0], unit[0] + unit[1], positions,
                        [SPACING[perm[0]], SPACING[perm[1]], SPACING[perm[2]]], bits=8, signed=False, names=names)


# The axis orders and signs each format is written with: (perm, sign), stored axis c -> patient axis perm[c].
ORDERS = {
    "lps": ((0, 1, 2), (1, 1, 1)),
    "ras": ((0, 1, 2), (-1, -1, 1)),
    "sagittal": ((1, 2, 0), (1, -1, -1)),
    "coronal": ((0, 2, 1), (-1, -1, 1)),
    "odd": ((2, 0, 1), (-1, 1, -1)),
}


def orient(out):
    os.makedirs(out, exist_ok=True)
    listed = []

    def add(name):
        listed.append(name)

    write_nrrd(os.path.join(out, "reference.nrrd"), *ORDERS["lps"])
    write_nrrd(os.path.join(out, "ras.nrrd"), *ORDERS["ras"], space="right-anterior-superior")
    add("ras.nrrd")
    write_nrrd(os.path.join(out, "sagittal.nrrd"), *ORDERS["sagittal"], encoding="gzip")
    add("sagittal.nrrd")
    write_nrrd(os.path.join(out, "odd-ascii.nrrd"), *ORDERS["odd"], space="right-anterior-superior", encoding="ascii")
    add("odd-ascii.nrrd")
    write_nrrd(os.path.join(out, "coronal-hex.nrrd"), *ORDERS["coronal"], encoding="hex")
    add("coronal-hex.nrrd")
    write_nifti(os.path.join(out, "ras-sform.nii"), *ORDERS["ras"])
    add("ras-sform.nii")
    write_nifti(os.path.join(out, "odd-qform.nii"), *ORDERS["odd"], form="qform")
    add("odd-qform.nii")
    write_nifti(os.path.join(out, "sagittal-qform.nii"), *ORDERS["sagittal"], form="qform")
    add("sagittal-qform.nii")
    write_nifti(os.path.join(out, "coronal-nifti2.nii"), *ORDERS["coronal"], version=2)
    add("coronal-nifti2.nii")
    write_nifti(os.path.join(out, "odd-nifti2-qform.nii"), *ORDERS["odd"], version=2, form="qform")
    add("odd-nifti2-qform.nii")
    write_metaimage(os.path.join(out, "sagittal.mhd"), *ORDERS["sagittal"])
    add("sagittal.mhd")
    write_metaimage(os.path.join(out, "odd.mha"), *ORDERS["odd"], local=True, compressed=True)
    add("odd.mha")
    write_metaimage(os.path.join(out, "coronal-anatomical.mha"), *ORDERS["coronal"], local=True, anatomical_only=True)
    add("coronal-anatomical.mha")
    if "--no-dicom" not in sys.argv:
        phantom_dicom(os.path.join(out, "dicom-ras"), *ORDERS["ras"])
        add("dicom-ras")
        phantom_dicom(os.path.join(out, "dicom-sagittal"), *ORDERS["sagittal"])
        add("dicom-sagittal")
        phantom_dicom(os.path.join(out, "dicom-odd"), *ORDERS["odd"])
        add("dicom-odd")
    with open(os.path.join(out, "list"), "w") as f:
        f.write("\n".join(listed) + "\n")


def ramp_slices(n, rows, cols, base, step):
    return [[base + step * (k * 7 + r * 3 + c) % 200 for r in range(rows) for c in range(cols)] for k in range(n)]


def dicom_cases(out):
    axial = [1, 0, 0, 0, 1, 0]

    def along(n, step, origin=(0.0, 0.0, 0.0), tilt=0.0):
        return [[origin[0], origin[1] + k * step * math.tan(math.radians(tilt)), origin[2] + k * step]
                for k in range(n)]

    # 16-bit signed with a rescale (CT in HU: -1024 + stored), file names in no order; the same as one multi-frame
    # file with its frames in another order, and as a NRRD
    values = [[(k * 37 + i * 11) % 900 - 300 for i in range(12 * 10)] for k in range(8)]
    names = ["z%02d.dcm" % ((k * 5) % 8) for k in range(8)]
    dicom_series(os.path.join(out, "ct16"), values, 10, 12, axial, along(8, 2.5, (-5, 7, -40)), (0.7, 0.8, 2.5),
                 slope=1.0, inter=-1024.0, names=names, description="CT HU")
    enhanced_ct(os.path.join(out, "ct16-multiframe.dcm"), values, 10, 12, axial, along(8, 2.5, (-5, 7, -40)),
                (0.7, 0.8, 2.5), 1.0, -1024.0, [3, 0, 7, 1, 6, 2, 5, 4])
    write_reference_nrrd(os.path.join(out, "ct16.nrrd"), values, 10, 12, (0.7, 0.8, 2.5), "int16", "h")
    # 8-bit unsigned, sagittal: a row runs towards P, a column towards I, the slices towards L
    values = [[(k * 29 + i * 7) % 256 for i in range(9 * 11)] for k in range(6)]
    dicom_series(os.path.join(out, "mr8"), values, 11, 9, [0, 1, 0, 0, 0, -1],
                 [[k * 1.5, 0, 0] for k in range(6)], (1.1, 1.2, 1.5), bits=8, signed=False,
                 description="MR 8-bit sagittal")
    write_reference_nrrd(os.path.join(out, "mr8.nrrd"), values, 11, 9, (1.1, 1.2, 1.5), "uint8", "B",
                         directions=[(0, 1, 0), (0, 0, -1), (1, 0, 0)])
    # a missing slice: positions 0, 2, 4, 8, 10 mm
    values = [[k] * 64 for k in range(6)]
    pos = along(6, 2.0)
    del pos[3]
    dicom_series(os.path.join(out, "gap"), values[:5], 8, 8, axial, pos, (1, 1, 2), description="gap")
    # a gantry tilt of 20 degrees
    dicom_series(os.path.join(out, "tilt"), values, 8, 8, axial, along(6, 2.0, tilt=20.0), (1, 1, 2),
                 description="tilt")
    # two series in one folder: 7 slices and 4 slices
    two = os.path.join(out, "two")
    dicom_series(two, [[100 + k] * 64 for k in range(7)], 8, 8, axial, along(7, 1.0), (1, 1, 1),
                 uid="1.2.826.0.1.3680043.2.1125.7", description="big one", names=["a%02d.dcm" % k for k in range(7)])
    dicom_series(two, [[200 + k] * 64 for k in range(4)], 8, 8, axial, along(4, 3.0), (1, 1, 3),
                 uid="1.2.826.0.1.3680043.2.1125.4", description="small one", names=["b%02d.dcm" % k for k in range(4)])
    # 120 slices: progress on stderr
    dicom_series(os.path.join(out, "many"), [[k % 100] * 16 for k in range(120)], 4, 4, axial, along(120, 1.0),
                 (1, 1, 1), description="many")
    # a lone slice (one slice is no volume)
    dicom_series(os.path.join(out, "one"), [[1] * 64], 8, 8, axial, along(1, 1.0), (1, 1, 1), description="one")
    # not DICOM at all
    os.makedirs(os.path.join(out, "empty"), exist_ok=True)
    with open(os.path.join(out, "empty", "readme.txt"), "w") as f:
        f.write("no images here\n")


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("orient", "dicom"):
        sys.stderr.write("usage: volumes.py orient|dicom DIR\n")
        sys.exit(2)
    random.seed(1)
    (orient if sys.argv[1] == "orient" else dicom_cases)(sys.argv[2])
