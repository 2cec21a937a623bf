/* SPDX-License-Identifier: MIT */
/*
 * slices.c: the windowed 8-bit volume, one padded copy per principal axis (see slices.h).
 *
 * Three copies cost three times the memory of the 8-bit volume, and buy reading every slice row front to back
 * in address order whatever the view, which is what makes compositing fast (Lacroute's reason too).
 */
#include "fixmath.h"
#include "slices.h"

static void window_into_z(const vf_volume_t *vol, vf_window_t w, uint8_t *out);
static void transpose_from_z(const uint8_t *z, const uint32_t dims[3], int k_axis, uint8_t *out);

void vfi_layout(const uint32_t dims[3], int k_axis, vfi_layout_t *l)
{
    l->i_axis = (k_axis + 1) % 3;
    l->j_axis = (k_axis + 2) % 3;
    l->ni = dims[l->i_axis];
    l->nj = dims[l->j_axis];
    l->nk = dims[k_axis];
    l->row = l->ni + 1;
    l->slice = l->row * (l->nj + 1);
}

size_t vfi_slices_bytes(const uint32_t dims[3], int k_axis)
{
    vfi_layout_t l;
    vfi_layout(dims, k_axis, &l);
    return (size_t)l.slice * l.nk;
}

uint8_t vfi_window_scalar(int32_t raw, vf_window_t w)
{
    /* round((v - lo) 255 / (hi - lo)) = floor((510 x + D) / 2D) for x = v - lo >= 0 and D = hi - lo > 0;
     * a descending window (hi < lo) is the same with both signs turned. */
    int64_t x = (int64_t)raw - w.lo, d = (int64_t)w.hi - w.lo;
    if (d < 0) {
        x = -x;
        d = -d;
    }
    if (x <= 0)
        return 0;
    if (x >= d)
        return 255;
    if (d < (INT64_C(1) << 22)) /* 510 x + d fits 32 bits: the common case, a 32-bit division */
        return (uint8_t)((uint32_t)(510 * x + d) / (uint32_t)(2 * d));
    return (uint8_t)vfi_udiv64((uint64_t)(510 * x + d), (uint64_t)(2 * d));
}

void vfi_slices_build(const vf_volume_t *vol, vf_window_t w, uint8_t *const copies[3])
{
    window_into_z(vol, w, copies[2]);
    transpose_from_z(copies[2], vol->dims, 0, copies[0]);
    transpose_from_z(copies[2], vol->dims, 1, copies[1]);
}

static void window_into_z(const vf_volume_t *vol, vf_window_t w, uint8_t *out)
{
    vfi_layout_t l;
    vfi_layout(vol->dims, 2, &l); /* i = x, j = y: the file's own order */
    /* 8-bit data goes through a 256-entry map; 16-bit data is divided voxel by voxel. */
    uint8_t map8[256];
    if (vol->type == VF_VOXEL_U8 || vol->type == VF_VOXEL_I8)
        for (int v = 0; v < 256; v++)
            map8[v] = vfi_window_scalar(vol->type == VF_VOXEL_U8 ? v : (int8_t)(uint8_t)v, w);
    size_t src = 0;
    for (uint32_t k = 0; k < l.nk; k++)
        for (uint32_t j = 0; j < l.nj; j++) {
            uint8_t *row = out + (size_t)k * l.slice + (size_t)j * l.row;
            for (uint32_t i = 0; i < l.ni; i++, src++) {
                switch (vol->type) {
                case VF_VOXEL_U8:
                case VF_VOXEL_I8: row[i] = map8[((const uint8_t *)vol->voxels)[src]]; break;
                case VF_VOXEL_U16: row[i] = vfi_window_scalar(((const uint16_t *)vol->voxels)[src], w); break;
                default: row[i] = vfi_window_scalar(((const int16_t *)vol->voxels)[src], w); break;
                }
            }
        }
    vfi_pad_copy(out, &l, 1);
}

/* Gather the copy for principal axis k_axis from the z copy: element (i, j, k) is object voxel p with
 * p[i_axis] = i, p[j_axis] = j, p[k_axis] = k. Elements of 1 or 2 bytes (elem), each a body of its own so that
 * the copy of the slices, which runs on every window change, moves bytes. */
static VF_ALWAYS_INLINE void transpose_body(const void *z, const uint32_t dims[3], int k_axis, void *out, size_t elem)
{
    vfi_layout_t lz, l;
    vfi_layout(dims, 2, &lz);
    vfi_layout(dims, k_axis, &l);
    size_t stride_obj[3] = {1, lz.row, lz.slice}; /* element step in the z copy per object axis */
    size_t si = stride_obj[l.i_axis], sj = stride_obj[l.j_axis], sk = stride_obj[k_axis];
    for (uint32_t k = 0; k < l.nk; k++)
        for (uint32_t j = 0; j < l.nj; j++) {
            const size_t dst = (size_t)k * l.slice + (size_t)j * l.row, src = k * sk + j * sj;
            if (elem == 1) {
                uint8_t *row = (uint8_t *)out + dst;
                const uint8_t *from = (const uint8_t *)z + src;
                for (uint32_t i = 0; i < l.ni; i++)
                    row[i] = from[i * si];
            } else {
                uint16_t *row = (uint16_t *)out + dst;
                const uint16_t *from = (const uint16_t *)z + src;
                for (uint32_t i = 0; i < l.ni; i++)
                    row[i] = from[i * si];
            }
        }
    vfi_pad_copy(out, &l, elem);
}

static void transpose_from_z(const uint8_t *z, const uint32_t dims[3], int k_axis, uint8_t *out)
{
    transpose_body(z, dims, k_axis, out, 1);
}

void vfi_transpose_copy(const void *z, const uint32_t dims[3], int k_axis, void *out, size_t elem)
{
    if (elem == 1)
        transpose_body(z, dims, k_axis, out, 1);
    else
        transpose_body(z, dims, k_axis, out, 2);
}

/* The extra column and row repeat the last real ones. */
void vfi_pad_copy(void *copy, const vfi_layout_t *l, size_t elem)
{
    for (uint32_t k = 0; k < l->nk; k++) {
        unsigned char *slice = (unsigned char *)copy + (size_t)k * l->slice * elem;
        for (uint32_t j = 0; j < l->nj; j++) {
            unsigned char *row = slice + (size_t)j * l->row * elem;
            for (size_t b = 0; b < elem; b++)
                row[l->ni * elem + b] = row[(l->ni - 1) * elem + b];
        }
        const unsigned char *last = slice + (size_t)(l->nj - 1) * l->row * elem;
        unsigned char *extra = slice + (size_t)l->nj * l->row * elem;
        for (size_t b = 0; b < (size_t)l->row * elem; b++)
            extra[b] = last[b];
    }
}
