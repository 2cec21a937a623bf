/* SPDX-License-Identifier: MIT */
/* lib_compare.c: a volume read by the formats' reference libraries, nifticlib (libnifti2: NIfTI-1 and -2) or teem's
 * nrrd, written back as a plain NRRD (raw, little-endian, the library's voxels as it stores them, with the library's
 * idea of where the axes point in the patient as LPS space directions), so that tests/port/libraries.sh can render
 * it with volfix next to the original: the same frame means volfix's reader and the library agree on the voxels,
 * their type, spacing and orientation. Built and run by that test (docs/formats.md says why volfix keeps its own
 * readers).
 *   lib_compare nifti|nrrd FILE OUT.nrrd   exit 0 and OUT written, 1 when the library refuses FILE (its message on
 *                                          stderr), 2 for a type or dimension volfix has no counterpart for
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <nifti/nifti2_io.h>
#include <teem/nrrd.h>

/* What is written: dims, a type name, voxels, and per axis an LPS vector spacing long (or only spacings). */
typedef struct {
    int64_t dims[3];
    const char *type;
    size_t bytes;
    const void *data;
    int oriented;
    double axes[3][3];
    double spacing[3];
} out_t;

static int write_nrrd(const char *path, const out_t *o)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 2;
    fprintf(f, "NRRD0004\ntype: %s\ndimension: 3\nsizes: %lld %lld %lld\n", o->type, (long long)o->dims[0],
            (long long)o->dims[1], (long long)o->dims[2]);
    if (o->oriented) {
        fprintf(f, "space: left-posterior-superior\nspace directions:");
        for (int a = 0; a < 3; a++)
            fprintf(f, " (%.17g,%.17g,%.17g)", o->axes[a][0], o->axes[a][1], o->axes[a][2]);
        fprintf(f, "\n");
    } else {
        fprintf(f, "spacings: %.17g %.17g %.17g\n", o->spacing[0], o->spacing[1], o->spacing[2]);
    }
    fprintf(f, "endian: little\nencoding: raw\n\n");
    size_t n = (size_t)(o->dims[0] * o->dims[1] * o->dims[2]) * o->bytes;
    int ok = fwrite(o->data, 1, n, f) == n;
    return fclose(f) == 0 && ok ? 0 : 2;
}

static int from_nifti(const char *file, const char *out)
{
    nifti_set_debug_level(0);
    nifti_image *nim = nifti_image_read(file, 1);
    if (!nim || !nim->data) {
        fprintf(stderr, "nifticlib: cannot read %s\n", file);
        return 1;
    }
    out_t o = {.dims = {nim->nx, nim->ny, nim->nz}, .data = nim->data, .bytes = (size_t)nim->nbyper};
    int rc = 0;
    switch (nim->datatype) {
    case DT_UINT8: o.type = "uint8"; break;
    case DT_INT8: o.type = "int8"; break;
    case DT_INT16: o.type = "int16"; break;
    case DT_UINT16: o.type = "uint16"; break;
    default: rc = 2; break;
    }
    if (nim->nt > 1 || nim->nu > 1)
        rc = 2; /* volfix reads the first volume of a 4D file; the library reads them all */
    /* pixdim's sign means nothing (the qform's qfac is pixdim[0]); nifticlib keeps it as written */
    o.spacing[0] = fabs(nim->dx);
    o.spacing[1] = fabs(nim->dy);
    o.spacing[2] = fabs(nim->dz);
    /* nifticlib's choice: the sform when its code is set, else the qform; NIfTI's world is RAS */
    const nifti_dmat44 *m = nim->sform_code > 0 ? &nim->sto_xyz : nim->qform_code > 0 ? &nim->qto_xyz : NULL;
    if (m) {
        o.oriented = 1;
        for (int a = 0; a < 3; a++) {
            o.axes[a][0] = -m->m[0][a];
            o.axes[a][1] = -m->m[1][a];
            o.axes[a][2] = m->m[2][a];
        }
    }
    if (rc == 0)
        rc = write_nrrd(out, &o);
    nifti_image_free(nim);
    return rc;
}

static int from_nrrd(const char *file, const char *out)
{
    Nrrd *n = nrrdNew();
    if (nrrdLoad(n, file, NULL)) {
        char *err = biffGetDone(NRRD);
        fprintf(stderr, "teem: %s", err);
        free(err);
        nrrdNuke(n);
        return 1;
    }
    int rc = 0;
    out_t o = {.data = n->data};
    switch (n->type) {
    case nrrdTypeUChar: o.type = "uint8"; o.bytes = 1; break;
    case nrrdTypeChar: o.type = "int8"; o.bytes = 1; break;
    case nrrdTypeShort: o.type = "int16"; o.bytes = 2; break;
    case nrrdTypeUShort: o.type = "uint16"; o.bytes = 2; break;
    default: rc = 2; break;
    }
    if (n->dim != 3)
        rc = 2;
    for (unsigned a = 0; a < 3 && a < n->dim; a++) {
        o.dims[a] = (int64_t)n->axis[a].size;
        o.spacing[a] = AIR_EXISTS(n->axis[a].spacing) ? n->axis[a].spacing : 1.0;
    }
    /* the patient spaces teem knows; a scanner space or none: as stored */
    int sign_x = 0, sign_y = 0;
    switch (n->space) {
    case nrrdSpaceLeftPosteriorSuperior: sign_x = sign_y = 1; break;
    case nrrdSpaceRightAnteriorSuperior: sign_x = sign_y = -1; break;
    default: break;
    }
    if (sign_x && n->spaceDim == 3) {
        o.oriented = 1;
        for (unsigned a = 0; a < 3; a++) {
            o.axes[a][0] = sign_x * n->axis[a].spaceDirection[0];
            o.axes[a][1] = sign_y * n->axis[a].spaceDirection[1];
            o.axes[a][2] = n->axis[a].spaceDirection[2];
        }
    } else if (n->spaceDim > 0) {
        for (unsigned a = 0; a < 3; a++) { /* spacing from the directions' lengths, as volfix takes it */
            double len = 0;
            for (unsigned c = 0; c < n->spaceDim; c++)
                len += n->axis[a].spaceDirection[c] * n->axis[a].spaceDirection[c];
            if (len > 0)
                o.spacing[a] = sqrt(len);
        }
    }
    if (rc == 0)
        rc = write_nrrd(out, &o);
    nrrdNuke(n);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 4 || (strcmp(argv[1], "nifti") && strcmp(argv[1], "nrrd"))) {
        fprintf(stderr, "usage: lib_compare nifti|nrrd FILE OUT.nrrd\n");
        return 2;
    }
    return strcmp(argv[1], "nifti") == 0 ? from_nifti(argv[2], argv[3]) : from_nrrd(argv[2], argv[3]);
}
